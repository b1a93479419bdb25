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

#include "functions.h"

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
