#pragma once
// The VRML97 output: the same scene with every FShape (and every top-level FTransform) replaced by
// a standard Shape holding an IndexedFaceSet (per-vertex colours and normals) or an IndexedLineSet,
// the FVRML PROTO declarations and the ROUTEs to replaced nodes dropped, everything else kept.
// One frame: the scene at the model's clock value.
#include <map>
#include <string>

#include "runtime/mesh/mesh.h"
#include "runtime/scene/scene_model.h"

namespace fscript::scene {

// `meshes`: the mesh of each replaced node (an FShape or a top-level FTransform), in the node's
// own coordinates. Returns the text of the file.
std::string export_vrml(const vrml::Scene& in, const std::map<const vrml::Node*, mesh::Mesh>& meshes);

}  // namespace fscript::scene
