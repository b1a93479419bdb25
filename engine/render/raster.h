#pragma once
// The software renderer: triangles and polylines of a mesh drawn with a z-buffer, per-vertex
// colours and normals, Phong shading with the mesh's material and supersampled anti-aliasing;
// implicit shapes drawn without meshing (direct.h) share the z-buffer, each sample ray-cast.
// Lights: the scene's DirectionalLights and the headlight by the VRML97 lighting model, or, when the
// scene has no lights, a headlight plus a key light. The camera comes from the scene's Viewpoint, or
// frames the mesh automatically (its outline about 80% of the picture).
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "backends/backend.h"
#include "engine/mesh/field.h"
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
  unsigned threads = 1;  // for the direct shapes
  bool prune = true;     // the direct shapes' interval descent (off: every step of every ray)
};

// A shape drawn without meshing (direct.h), into the same depth buffer as the meshes.
struct DirectShape {
  const mesh::Field* field = nullptr;  // inside where f >= 0, in the shape's own coordinates
  std::array<double, 6> box{};         // the shape's box there (x0, x1, y0, y1, z0, z1)
  std::array<double, 16> to_world{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // column-major, affine
  std::array<double, 6> extent{};      // a box in the world holding all of it that shows
  std::vector<mesh::Vec3> outline;     // points in the world around it, for the automatic camera
  // The colours at points of the shape (its own coordinates); none: the material's diffuse colour.
  std::function<bool(const std::vector<std::array<float, 3>>&, std::vector<std::array<float, 3>>&,
                     backends::RuntimeError&)>
      colour;
  std::optional<mesh::Material> material;
};

// RGB pixels, row-major from the top row.
std::vector<uint8_t> render(const mesh::Mesh& m, const RenderOptions& opts);
// The meshes and the direct shapes in one picture; false on a runtime error of direct shape
// `failed` (then `err` says what).
bool render(const mesh::Mesh& m, const std::vector<DirectShape>& direct, const RenderOptions& opts,
            std::vector<uint8_t>& out, backends::RuntimeError& err, size_t& failed);

}  // namespace fscript::render
