/* The shared benchmark functions in C evaluated row by row over the dense grid of
 * `fscript bench --grid` (issue 19's baseline): the x loop innermost with y, z and t fixed, the
 * function inlined, so the compiler hoists what does not depend on x out of the row, as our row
 * split does. One thread, best of five runs, nanoseconds per point. Built by bench/c/run.sh.
 * usage: shapes gyroid|csg8 [points] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

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

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + ts.tv_nsec * 1e-9;
}

#define ROWS(F)                                                      \
  for (size_t r = 0; r < rows; ++r) {                                \
    float y = ys[r], z = zs[r], *o = out + r * side;                 \
    for (size_t i = 0; i < side; ++i) o[i] = F(xs[i], y, z, 0.0f);   \
  }

int main(int argc, char** argv) {
  if (argc < 2 || (strcmp(argv[1], "gyroid") && strcmp(argv[1], "csg8"))) {
    fprintf(stderr, "usage: %s gyroid|csg8 [points]\n", argv[0]);
    return 2;
  }
  int is_gyroid = !strcmp(argv[1], "gyroid");
  size_t n = argc > 2 ? strtoul(argv[2], NULL, 10) : 2000000;
  size_t side = (size_t)ceil(cbrt((double)n));
  if (side < 2) side = 2;
  size_t rows = (n + side - 1) / side;
  float *xs = malloc(side * 4), *ys = malloc(rows * 4), *zs = malloc(rows * 4), *out = malloc(rows * side * 4);
  for (size_t i = 0; i < side; ++i) xs[i] = -1.0f + 2.0f * (float)i / (float)(side - 1);
  for (size_t r = 0; r < rows; ++r) {
    ys[r] = -1.0f + 2.0f * (float)(r % side) / (float)(side - 1);
    zs[r] = -1.0f + 2.0f * (float)((r / side) % side) / (float)(side - 1);
  }
  double best = 1e30, sum = 0;
  for (int run = 0; run < 5; ++run) {
    double t0 = now();
    if (is_gyroid) ROWS(gyroid) else ROWS(csg8)
    double dt = now() - t0;
    if (dt < best) best = dt;
    for (size_t i = 0; i < rows * side; ++i) sum += out[i];
  }
  printf("%.2f ns/point (checksum %.6g)\n", best * 1e9 / (double)(rows * side), sum);
  free(xs), free(ys), free(zs), free(out);
  return 0;
}
