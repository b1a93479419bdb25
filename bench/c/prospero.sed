# Turns ../shared/data/prospero.fs into C over four lanes (SSE intrinsics, what gcc makes of the
# same code written with float vectors): one statement per line, as the file has them.
/^\/\//d
s/^function FRep\(x, y, z, t\) \{/static __m128 frep(__m128 x, __m128 y) {/
s/^  var (_[0-9a-f]+) = (-?[0-9.e+-]+);/  const __m128 \1 = _mm_set1_ps((float)\2);/
s/^  var (_[0-9a-f]+) = ([xy]);/  const __m128 \1 = \2;/
s/^  var (_[0-9a-f]+) = (_[0-9a-f]+) \* (_[0-9a-f]+);/  const __m128 \1 = _mm_mul_ps(\2, \3);/
s/^  var (_[0-9a-f]+) = (_[0-9a-f]+) \+ (_[0-9a-f]+);/  const __m128 \1 = _mm_add_ps(\2, \3);/
s/^  var (_[0-9a-f]+) = (_[0-9a-f]+) - (_[0-9a-f]+);/  const __m128 \1 = _mm_sub_ps(\2, \3);/
s/^  var (_[0-9a-f]+) = -(_[0-9a-f]+);/  const __m128 \1 = _mm_xor_ps(\2, _mm_set1_ps(-0.0f));/
s/^  var (_[0-9a-f]+) = (max|min|sqrt)\(/  const __m128 \1 = _mm_\2_ps(/
s/^  return -(_[0-9a-f]+);/  return _mm_xor_ps(\1, _mm_set1_ps(-0.0f));/
