#pragma once
// The VRML97 output: the same scene with every FShape (and every top-level FTransform) replaced by
// a standard Shape holding an IndexedFaceSet (per-vertex colours and normals) or an IndexedLineSet,
// the FVRML PROTO declarations and the ROUTEs to replaced nodes dropped, everything else kept.
// An animated node becomes a Group of its frames under a Switch, a TimeSensor with the node's own
// timing and a small Script (JavaScript, with a CastleScript twin for browsers without JavaScript)
// that turns the fraction into the frame; a TimeSensor routed to the node's set_fraction drives the
// Script instead, which takes over the node's DEF name so such ROUTEs stay valid.
#include <map>
#include <string>

#include "engine/mesh/frame_cache.h"
#include "engine/mesh/mesh.h"
#include "engine/scene/scene_model.h"

namespace fscript::scene {

struct Animation {
  const mesh::FrameCache* frames = nullptr;  // frame i at fraction i / N, every frame cached
  TimeSensorFields timing;                   // the node's own cycle
  bool external = false;                     // a TimeSensor routed to the node's set_fraction drives it
  int initial = 0;                           // the frame shown before the first event
};

// `meshes`: the mesh of each replaced node (an FShape or a top-level FTransform), in the node's
// own coordinates; `animations`: the replaced nodes shown as frames. With `output_path`, relative
// URLs (Inline, EXTERNPROTO, textures) are rewritten to name the same files from its folder.
// Returns the text of the file.
std::string export_vrml(const vrml::Scene& in, const std::map<const vrml::Node*, mesh::Mesh>& meshes,
                        const std::map<const vrml::Node*, Animation>& animations = {},
                        const std::string& output_path = "");

}  // namespace fscript::scene
