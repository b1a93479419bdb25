#pragma once
// fscript profile: where a shape's evaluation goes while it is meshed, by source line (the share of
// the time and of the operations evaluated after pruning), with the pruning figures and a picture.
#include <string>

#include "backends/backend.h"

namespace fscript::cli {

struct ProfileArgs {
  std::string file, backend = "auto", picture;
  double resolution_scale = 1;
  unsigned threads = 1;
  bool prune = true, json = false;
  backends::Budgets budgets;  // fscript's budget flags
};

// Meshes every implicit shape of the .fs script or .wrl scene as fvrml-run does, profiled; the
// report on standard output. Exit 1 on a bad file or a runtime error (diagnostics on stderr).
int cmd_profile(const ProfileArgs& a);

}  // namespace fscript::cli
