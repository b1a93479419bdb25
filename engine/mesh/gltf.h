#pragma once
// glTF 2.0 binary (.glb): meshes with positions, unit normals, per-vertex colours (COLOR_0), 32-bit
// indices, triangles or lines for curves; the static geometry in one node, and each animated shape
// as frame nodes switched by a STEP animation of their scales over one cycle.
#include <string>
#include <vector>

#include "engine/mesh/mesh.h"

namespace fscript::mesh {

struct GltfAnimation {
  std::string name;
  std::vector<Mesh> frames;    // frame k shown during [k T / N, (k + 1) T / N)
  double cycle_interval = 1;   // T, seconds
  // When given (one per frame, rising from 0): frame k shown from starts[k] to the next start, the
  // last until T. The live preview's animation while only some frames exist.
  std::vector<double> starts;
};

std::string encode_glb(const Mesh& m, const std::vector<GltfAnimation>& animations = {});

}  // namespace fscript::mesh
