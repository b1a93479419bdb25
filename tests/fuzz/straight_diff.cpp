// Fuzz target: backend_diff on straight-line programs (program_gen's straight_line: no loops,
// recursion or arrays; helpers inlined and ifs converted, so the kernel is mostly one block). That
// is the code the SSE emitter runs on eight lanes and the VM reorders and fuses, which
// backend_diff's programs, with their loops, calls and arrays, seldom are.
#define FS_DIFF_STRAIGHT_LINE true
#include "tests/fuzz/backend_diff.cpp"
