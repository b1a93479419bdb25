#pragma once
// What a shape costs before any work is done: the points its polygonizer evaluates and the memory
// they need, by the shape's own dimension (docs/scenes.md, "Limits"). Scenes are refused by these,
// not by a resolution per axis: a curve of 20,000 samples is a few hundred kilobytes.
#include <array>
#include <cstdint>
#include <string>

namespace fscript::scene {

enum class ShapeKind;

struct ShapeCost {
  double samples = 0;  // points evaluated for one frame
  double bytes = 0;    // memory that frame needs while it is made (at least, for implicit shapes)
  double kept = 0;     // bytes of a finished parametric frame an animation keeps (frame_cache.h)
};

// The cost of one frame of a shape of `kind` at `resolution` intervals per axis (doubles, so a
// resolution of 1e12 is measured, not overflowed).
ShapeCost shape_cost(ShapeKind kind, const std::array<double, 3>& resolution);

// The most points one shape or one run may evaluate: a 4096^3 grid (about 10 minutes of a long
// function on one core). Parametric shapes are bounded by memory first (every point is a vertex of
// the output), and by 10^9 points, so that twice as many triangles stay within the writers'
// 32-bit counts and indices.
constexpr double kMaxShapeSamples = 4097.0 * 4097.0 * 4097.0;
constexpr double kMaxParametricSamples = 1e9;
// The memory the memory limit allows (`max_memory_mib`, 0: --max-memory's default).
double memory_limit_bytes(uint64_t max_memory_mib);

// "1.2 GiB", "350 MiB", "12 KiB".
std::string bytes_text(double bytes);

}  // namespace fscript::scene
