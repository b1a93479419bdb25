#pragma once
// The light on a surface point, shared by the rasteriser and the direct renderer so a shape looks
// the same drawn either way: the scene's DirectionalLights and headlight by the VRML97 lighting
// model, or, when the scene has no lights, a headlight plus a key light above the camera.
#include <array>
#include <optional>
#include <vector>

#include "engine/mesh/mesh.h"

namespace fscript::render {

using V3 = std::array<double, 3>;

struct Light {  // a VRML97 DirectionalLight in world coordinates
  std::array<float, 3> direction{0, 0, -1}, colour{1, 1, 1};
  float intensity = 1, ambient = 0;
};

struct Shading {
  std::vector<Light> lights;  // none: the built-in key light
  bool headlight = true;
  std::optional<mesh::Material> material;  // none: the viewer's default (white highlights)
  V3 right{1, 0, 0}, up{0, 1, 0}, back{0, 0, 1};  // the camera's frame: the key light hangs on it
  // Two-sided: a normal facing away from the viewer is turned round.
  std::array<float, 3> shade(std::array<float, 3> base, V3 normal, V3 view_dir) const;
};

// Shading seen along one direction (a picture whose rays are parallel): the key light's vectors
// worked out once instead of per pixel, the same values as Shading::shade.
class FixedViewShading {
 public:
  FixedViewShading(const Shading& s, V3 view_dir);
  std::array<float, 3> shade(std::array<float, 3> base, V3 normal) const;

 private:
  const Shading& s_;
  V3 view_, key_{}, hv_{};
};

}  // namespace fscript::render
