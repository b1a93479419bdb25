/* The shared benchmark functions in C (../../../shared/bench/gyroid.fs and csg8.fs), for
 * baseline.c (point by point) and shapes.c (row by row). static inline: each caller's loop gets
 * them inlined, so a compiler may hoist what does not change. */
#include <math.h>

static inline float gyroid(float x, float y, float z, float t) {
  float k = 6.283185307179586f * 2.0f;
  float X = x * k + t, Y = y * k, Z = z * k;
  return sinf(X) * cosf(Y) + sinf(Y) * cosf(Z) + sinf(Z) * cosf(X);
}

static inline float smin(float a, float b, float k) {
  float h = fmaxf(k - fabsf(a - b), 0.0f) / k;
  return fminf(a, b) - h * h * k * 0.25f;
}
static inline float sphere(float x, float y, float z, float cx, float cy, float cz, float r) {
  float dx = x - cx, dy = y - cy, dz = z - cz;
  return sqrtf(dx * dx + dy * dy + dz * dz) - r;
}
static inline float csg8(float x, float y, float z, float t) {
  float d = sphere(x, y, z, 0.5f + 0.1f * t, 0.0f, 0.0f, 0.3f);
  d = smin(d, sphere(x, y, z, -0.5f, 0.0f, 0.0f, 0.3f), 0.2f);
  d = smin(d, sphere(x, y, z, 0.0f, 0.5f, 0.0f, 0.3f), 0.2f);
  d = smin(d, sphere(x, y, z, 0.0f, -0.5f, 0.0f, 0.3f), 0.2f);
  d = smin(d, sphere(x, y, z, 0.0f, 0.0f, 0.5f, 0.3f), 0.2f);
  d = smin(d, sphere(x, y, z, 0.0f, 0.0f, -0.5f, 0.3f), 0.2f);
  d = smin(d, sphere(x, y, z, 0.35f, 0.35f, 0.35f, 0.25f), 0.2f);
  d = smin(d, sphere(x, y, z, -0.35f, -0.35f, -0.35f, 0.25f), 0.2f);
  d = fmaxf(d, -sphere(x, y, z, 0.0f, 0.0f, 0.0f, 0.2f));
  float box = fmaxf(fabsf(x) - 0.7f, fmaxf(fabsf(y) - 0.7f, fabsf(z) - 0.7f));
  return -fmaxf(d, box);
}
