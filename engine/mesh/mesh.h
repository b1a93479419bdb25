#pragma once
// The mesh type shared by polygonizers, writers, the renderer and fvrml-meshdiff: indexed
// triangles (or polylines for curves) with optional per-vertex normals and colours.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace fscript::mesh {

using Vec3 = std::array<float, 3>;

// The standard VRML97 Material of a shape (FMaterial's strings evaluated once per frame).
struct Material {
  Vec3 diffuse{0.8f, 0.8f, 0.8f}, emissive{0, 0, 0}, specular{0, 0, 0};
  float ambient_intensity = 0.2f, shininess = 0.2f, transparency = 0;
  bool operator==(const Material&) const = default;
};

struct Mesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  // empty or one per position
  std::vector<Vec3> colours;  // empty or one per position, each channel in [0, 1]
  std::vector<Vec3> params;   // parametric shapes: the (u, v, w) of each position
  // Empty, or per position the vertex it was split from to carry another normal (its own index
  // where it was not): the same point of the surface (dc_normals.h). topology() welds them back and
  // the OBJ writer writes each point once.
  std::vector<uint32_t> split_from;
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<std::vector<uint32_t>> polylines;  // curves
  std::optional<Material> material;              // none: the viewer's default

  void append(const Mesh& other);  // concatenates (indices shifted)
};

// Topology report of the surface, the copies of a vertex split for its normals welded back
// (Mesh::split_from): every edge shared by exactly two triangles
// (watertight), each used once in each direction (consistently oriented), no vertex whose
// triangles form more than one fan (2-manifold), V - E + F, and the connected components, with
// those whose signed volume is negative (inside-out, or the wall of a cavity).
struct Topology {
  bool watertight = false;
  bool oriented = false;
  bool manifold = false;
  long euler = 0;
  size_t boundary_edges = 0;
  size_t degenerate_triangles = 0;
  size_t components = 0;
  size_t inverted_components = 0;
};
Topology topology(const Mesh& m);

// Normals per triangle corner (3 per triangle) for shading a mesh that has no vertex normals (dual
// contouring's): the area-weighted mean of the normals of the triangles around the corner's vertex
// that meet its own triangle's within `crease` radians, as VRML97's creaseAngle does; so smooth
// surfaces shade smooth and sharp edges stay sharp.
std::vector<Vec3> crease_normals(const Mesh& m, double crease);
// The crease angle our pictures and VRML97 files use (40 degrees): CSG edges are sharper, the
// faces of a curved surface meshed at the usual resolutions meet at less.
constexpr double kCreaseAngle = 0.7;

}  // namespace fscript::mesh
