#pragma once
// The fscript subcommands; each returns the process exit status (CLI contract: 0, 1 or 2).
#include <cstdint>
#include <string>
#include <vector>

#include "tools/fscript/common.h"

namespace fscript::cli {

int cmd_run(const Options& o, const std::string& file, const std::string& entry, const std::vector<std::string>& args);
int cmd_eval(const Options& o, const std::string& file, const std::string& entry, const std::string& points);
int cmd_check(const std::vector<std::string>& files);
int cmd_emit_ir(const std::string& file, const std::string& entry, bool opt, const std::string& passes, bool llvm,
                bool gradient);
int cmd_emit_asm(const Options& o, const std::string& file, const std::string& entry);
// Prints the canonical formatting; -i rewrites the file (only if it changes), --check only says.
int cmd_fmt(const std::string& file, bool in_place, bool check_only);
// How bench calls the kernel: batches of points, one point per call, or rows of the grid.
enum class BenchPath { Batch, OnePoint, Grid };
int cmd_bench(const Options& o, const std::string& file, const std::string& entry, size_t points, unsigned threads,
              BenchPath path);
int cmd_render2d(const Options& o, const std::string& file, const std::string& entry, const std::string& size,
                 const std::string& bounds, const std::string& out_path, unsigned threads, bool prune, bool stats,
                 unsigned repeat);
// render3d's choices (main.cpp documents each flag).
struct Render3dArgs {
  std::string file, entry, size, bounds = "-1,1,-1,1,-1,1", view, image = "shaded", out;
  uint32_t steps = 0;  // 0: the picture's larger side
  unsigned threads = 1, repeat = 1;
  bool prune = true, stats = false;
};
int cmd_render3d(const Options& o, const Render3dArgs& a);

}  // namespace fscript::cli
