/* The Prospero image in C, four lanes at a time (bench/c/run.sh generates prospero_body.h from
 * ../shared/data/prospero.fs with prospero.sed): the 1024^2 render of `fscript render2d ... --size
 * 1024 --bounds -1,1,-1,1`, brute force, one thread, best of five, and its count of inside pixels. */
#include <immintrin.h>
#include <stdio.h>
#include <time.h>

#include "prospero_body.h"

enum { kSide = 1024 };
static float image[kSide * kSide];

static double now_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

int main(void) {
  double best = 1e30;
  for (int run = 0; run < 5; ++run) {
    double start = now_ms();
    for (int j = 0; j < kSide; ++j) {
      __m128 y = _mm_set1_ps(1.0f - 2.0f * (float)j / (kSide - 1));
      for (int i = 0; i < kSide; i += 4) {
        float xs[4];
        for (int k = 0; k < 4; ++k) xs[k] = -1.0f + 2.0f * (float)(i + k) / (kSide - 1);
        _mm_storeu_ps(image + j * kSide + i, frep(_mm_loadu_ps(xs), y));
      }
    }
    double ms = now_ms() - start;
    if (ms < best) best = ms;
  }
  int inside = 0;
  for (int i = 0; i < kSide * kSide; ++i) inside += image[i] >= 0.0f;
  printf("%.1f ms (%d inside pixels)\n", best, inside);
  return 0;
}
