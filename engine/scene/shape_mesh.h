#pragma once
// A resolved shape to a mesh in world coordinates: the polygonizer its kind calls for, vertex
// colours from FMaterial.diffuseColor (r, g, b, or the value through patternKey/patternColor like a
// VRML ColorInterpolator), and the enclosing Transforms applied.
#include "engine/mesh/marching_tetrahedra.h"
#include "engine/mesh/mesh.h"
#include "engine/scene/scene_model.h"

namespace fscript::scene {

// `world`: apply the enclosing Transforms (files of meshes); false keeps the shape's own
// coordinates (the VRML97 output keeps the Transform nodes).
bool mesh_shape(const Shape& s, mesh::Mesh& out, backends::RuntimeError& err, bool world = true, int threads = 1,
                bool prune = true, const mesh::MesherOptions& mesher = {});

// A top-level FTransform: its combined implicit field polygonized over the union of the children's
// boxes, coloured by its first shape's material.
bool mesh_group(const SceneModel& m, int group, mesh::Mesh& out, backends::RuntimeError& err, bool world = true,
                int threads = 1, bool prune = true, const mesh::MesherOptions& mesher = {});

// Positions by the matrix, normals by its inverse transpose; a mirroring matrix flips the winding.
void transform_mesh(const Mat4& t, mesh::Mesh& m);

// The colours FMaterial.diffuseColor gives at points of the shape (its own coordinates; u, v, w
// from `params`, or the point where there are none); `out` empty where it has no colour function.
bool colour_points(const Shape& s, const std::vector<mesh::Vec3>& points, const std::vector<mesh::Vec3>* params,
                   std::vector<mesh::Vec3>& out, backends::RuntimeError& err);
// FMaterial's other strings at the shape's frame as the VRML97 Material (none without an FMaterial).
bool shape_material(const Shape& s, std::optional<mesh::Material>& out, backends::RuntimeError& err);

// The pattern map: piecewise linear over keys, clamped at the ends; no pattern: a grey level.
mesh::Vec3 pattern_colour(const vrml::Node* material, float value);

}  // namespace fscript::scene
