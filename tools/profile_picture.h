#pragma once
// The profile's picture written as a PNG (fscript profile --picture, fvrml-run --profile-picture).
#include <string>

#include "engine/render/png.h"
#include "engine/scene/shape_profile.h"

namespace fscript::tools {

inline bool write_profile_picture(const mesh::FieldProfile& p, const std::string& path, std::string& error) {
  uint32_t w = 0, h = 0;
  std::vector<uint8_t> px = scene::profile_picture(p, w, h);
  if (px.empty()) return error = "nothing was evaluated to draw", false;
  return render::write_png(path, w, h, 3, px, error);
}

}  // namespace fscript::tools
