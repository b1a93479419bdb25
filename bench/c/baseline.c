/* The shared benchmark functions written in C, the baseline the JIT backends are measured against
 * (issues 5 and 6): the same dense grid over [-1, 1]^3 as `fscript bench`, one thread, best of
 * five runs, nanoseconds per point. Built by bench/c/run.sh with the compiler and flags it names.
 * usage: baseline gyroid|csg8 [points] */
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

int main(int argc, char** argv) {
  if (argc < 2 || (strcmp(argv[1], "gyroid") && strcmp(argv[1], "csg8"))) {
    fprintf(stderr, "usage: %s gyroid|csg8 [points]\n", argv[0]);
    return 2;
  }
  float (*f)(float, float, float, float) = strcmp(argv[1], "gyroid") ? csg8 : gyroid;
  size_t n = argc > 2 ? strtoul(argv[2], NULL, 10) : 2000000;
  size_t side = (size_t)ceil(cbrt((double)n));
  if (side < 2) side = 2;
  float *x = malloc(n * 4), *y = malloc(n * 4), *z = malloc(n * 4), *out = malloc(n * 4);
  for (size_t i = 0; i < n; ++i) {
    x[i] = -1.0f + 2.0f * (float)(i % side) / (float)(side - 1);
    y[i] = -1.0f + 2.0f * (float)((i / side) % side) / (float)(side - 1);
    z[i] = -1.0f + 2.0f * (float)((i / side / side) % side) / (float)(side - 1);
  }
  double best = 1e30, sum = 0;
  for (int run = 0; run < 5; ++run) {
    double t0 = now();
    for (size_t i = 0; i < n; ++i) out[i] = f(x[i], y[i], z[i], 0.0f);
    double dt = now() - t0;
    if (dt < best) best = dt;
    for (size_t i = 0; i < n; ++i) sum += out[i];
  }
  printf("%.2f ns/point (checksum %.6g)\n", best * 1e9 / (double)n, sum);
  free(x), free(y), free(z), free(out);
  return 0;
}
