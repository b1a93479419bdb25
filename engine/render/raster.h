#pragma once
// The software renderer: triangles and polylines of a mesh drawn with a z-buffer, per-vertex
// colours and normals, Phong shading with the mesh's material and supersampled anti-aliasing.
// Lights: the scene's DirectionalLights and the headlight by the VRML97 lighting model, or, when the
// scene has no lights, a headlight plus a key light. The camera comes from the scene's Viewpoint, or
// frames the mesh automatically (its outline about 80% of the picture).
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "engine/mesh/mesh.h"
#include "engine/render/shading.h"

namespace fscript::render {

struct Camera {
  std::array<double, 3> position{0, 0, 10};
  std::array<double, 4> orientation{0, 0, 1, 0};  // VRML SFRotation
  double field_of_view = 0.785398;
};

struct RenderOptions {
  uint32_t width = 800, height = 600;
  int supersample = 3;                           // samples per pixel per axis
  std::optional<Camera> camera;                  // none: frame the mesh automatically
  // Automatic framing (no camera, or `view_given`): looking at the mesh from azimuth (degrees about
  // +y, from +z toward +x) and elevation (degrees above the horizon), at the distance where its
  // outline fills about 80% of the picture's smaller side; `zoom` > 1 comes closer (with a camera,
  // it narrows the field of view instead).
  double azimuth = 30, elevation = 20, zoom = 1;
  bool view_given = false;  // --view: the automatic framing even when the scene has a Viewpoint
  std::array<float, 3> background{1, 1, 1};
  std::array<float, 3> default_colour{0.8f, 0.8f, 0.8f};  // the Material default diffuseColor
  std::vector<Light> lights;                     // the scene's; none: the built-in key light
  bool headlight = true;                         // NavigationInfo.headlight
  // A mesh without vertex normals (dual contouring's) shades smooth across edges whose faces meet
  // within this angle (radians; VRML97's creaseAngle) and sharp across the others.
  double crease_angle = mesh::kCreaseAngle;
};

// RGB pixels, row-major from the top row.
std::vector<uint8_t> render(const mesh::Mesh& m, const RenderOptions& opts);

}  // namespace fscript::render
