/* The Prospero image in C, four lanes at a time with SSE or sixteen with AVX-512 (bench/c/run.sh
 * generates prospero_body.h from ../shared/data/prospero.fs with prospero.sed): the 1024^2 render
 * of `fscript render2d ... --size 1024 --bounds -1,1,-1,1`, brute force, one thread, best of five,
 * and its count of inside pixels. min/max are the plain instructions (no NaN rule). */
#include <immintrin.h>
#include <stdio.h>
#include <time.h>

#ifdef __AVX512F__
enum { kLanes = 16 };
typedef __m512 V;
#define SET _mm512_set1_ps
#define ADD _mm512_add_ps
#define SUB _mm512_sub_ps
#define MUL _mm512_mul_ps
#define MAX _mm512_max_ps
#define MIN _mm512_min_ps
#define SQRT _mm512_sqrt_ps
#define NEG(a) _mm512_xor_ps(a, _mm512_set1_ps(-0.0f))
#define LOAD _mm512_loadu_ps
#define STORE _mm512_storeu_ps
#else
enum { kLanes = 4 };
typedef __m128 V;
#define SET _mm_set1_ps
#define ADD _mm_add_ps
#define SUB _mm_sub_ps
#define MUL _mm_mul_ps
#define MAX _mm_max_ps
#define MIN _mm_min_ps
#define SQRT _mm_sqrt_ps
#define NEG(a) _mm_xor_ps(a, _mm_set1_ps(-0.0f))
#define LOAD _mm_loadu_ps
#define STORE _mm_storeu_ps
#endif

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
      V y = SET(1.0f - 2.0f * (float)j / (kSide - 1));
      for (int i = 0; i < kSide; i += kLanes) {
        float xs[kLanes];
        for (int k = 0; k < kLanes; ++k) xs[k] = -1.0f + 2.0f * (float)(i + k) / (kSide - 1);
        STORE(image + j * kSide + i, frep(LOAD(xs), y));
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
