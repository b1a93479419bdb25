// The cost model of shapes (shape_cost.h). The bytes per point were measured on fvrml-run's peak
// memory (docs/scenes.md, "Limits"): a parametric point holds its evaluation, its vertex (position,
// normal, parameters, colour), two triangles and the writer's copy.
#include "engine/scene/shape_cost.h"

#include <cstdio>

#include "engine/scene/scene_model.h"
#include "runtime/support/limits.h"

namespace fscript::scene {
namespace {

constexpr double kSurfaceBytes = 320;  // per point of a parametric surface (or a solid's faces)
constexpr double kCurveBytes = 96;     // per point of a curve: a polyline vertex
constexpr double kPlaneBytes = 48;     // per point of an implicit grid's plane: the meshers' slabs
constexpr double kKeptBytes = 24;      // per vertex of a frame an animation keeps (compact)

}  // namespace

ShapeCost shape_cost(ShapeKind kind, const std::array<double, 3>& r) {
  double n[3];
  for (int k = 0; k < 3; ++k) n[k] = (r[k] < 1 ? 1 : r[k]) + 1;
  ShapeCost c;
  switch (kind) {
    case ShapeKind::Implicit: {
      c.samples = n[0] * n[1] * n[2];
      double plane = (n[0] + 2) * (n[1] + 2);
      // What the surface adds is not known before meshing: the run's memory limit stops it.
      c.bytes = kPlaneBytes * plane;
      return c;
    }
    case ShapeKind::Curve:
      c.samples = n[0];
      c.bytes = kCurveBytes * c.samples;
      c.kept = kKeptBytes * c.samples;
      return c;
    case ShapeKind::Surface: c.samples = n[0] * n[1]; break;
    case ShapeKind::Solid: c.samples = 2 * (n[0] * n[1] + n[1] * n[2] + n[2] * n[0]); break;
  }
  c.bytes = kSurfaceBytes * c.samples;
  c.kept = kKeptBytes * c.samples;
  return c;
}

double memory_limit_bytes(uint64_t max_memory_mib) {
  uint64_t mib = max_memory_mib ? max_memory_mib : support::default_memory_limit_mib();
  return static_cast<double>(mib) * 1048576.0;
}

std::string bytes_text(double bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (bytes >= 1024 && u < 6) bytes /= 1024, ++u;
  char buf[48];
  std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.3g %s", bytes, units[u]);
  return buf;
}

}  // namespace fscript::scene
