#pragma once
// Distances between two meshes' surfaces, for fvrml-meshdiff and the tests: every vertex and
// triangle centroid of one mesh is measured to the nearest point of the other's triangles (a
// uniform grid finds candidates). Hausdorff is the larger of the two directed maxima; Chamfer the
// mean of the two directed means.
#include "engine/mesh/mesh.h"

namespace fscript::mesh {

struct Distances {
  double hausdorff = 0, chamfer = 0;
  double max_ab = 0, max_ba = 0, mean_ab = 0, mean_ba = 0;
};

Distances mesh_distances(const Mesh& a, const Mesh& b);

// The diagonal of a mesh's bounding box.
double bbox_diagonal(const Mesh& m);

}  // namespace fscript::mesh
