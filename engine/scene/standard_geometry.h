#pragma once
// The scene's standard VRML97 geometry as meshes for pictures: IndexedFaceSet (per-vertex or
// per-face colours, flat faces unless the file gives normals), IndexedLineSet, Box, Sphere,
// Cylinder and Cone, with their Material and the enclosing Transforms. Text, PointSet,
// ElevationGrid and Extrusion are not drawn; Inline is not fetched.
#include <array>
#include <optional>
#include <vector>

#include "frontend/vrml/scene_graph.h"
#include "engine/mesh/mesh.h"

namespace fscript::scene {

// One mesh per standard Shape of the scene (FVRML nodes are skipped), in world coordinates.
std::vector<mesh::Mesh> standard_meshes(const vrml::Scene& scene);

// The first Background's sky colour, if any.
std::optional<std::array<float, 3>> background_colour(const vrml::Scene& scene);

}  // namespace fscript::scene
