# Turns ../shared/data/prospero.fs into C over a vector of lanes (the macros V, SET, ADD... that
# prospero_main.c defines with SSE or AVX-512 intrinsics): one statement per line, as the file has.
/^\/\//d
s/^function FRep\(x, y, z, t\) \{/static V frep(V x, V y) {/
s/^  var (_[0-9a-f]+) = (-?[0-9.e+-]+);/  const V \1 = SET((float)\2);/
s/^  var (_[0-9a-f]+) = ([xy]);/  const V \1 = \2;/
s/^  var (_[0-9a-f]+) = (_[0-9a-f]+) \* (_[0-9a-f]+);/  const V \1 = MUL(\2, \3);/
s/^  var (_[0-9a-f]+) = (_[0-9a-f]+) \+ (_[0-9a-f]+);/  const V \1 = ADD(\2, \3);/
s/^  var (_[0-9a-f]+) = (_[0-9a-f]+) - (_[0-9a-f]+);/  const V \1 = SUB(\2, \3);/
s/^  var (_[0-9a-f]+) = -(_[0-9a-f]+);/  const V \1 = NEG(\2);/
s/^  var (_[0-9a-f]+) = max\(/  const V \1 = MAX(/
s/^  var (_[0-9a-f]+) = min\(/  const V \1 = MIN(/
s/^  var (_[0-9a-f]+) = sqrt\(/  const V \1 = SQRT(/
s/^  return -(_[0-9a-f]+);/  return NEG(\1);/
