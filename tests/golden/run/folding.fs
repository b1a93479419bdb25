// Identities the optimiser may use, and the look-alikes it must not: every case runs before and
// after optimisation, constant expressions folded through the reference evaluator.
function a(x) { return 0 - x; }
function b(x) { return 1 / x; }
function c(x) { return x / 1 + x * 1 + 1 * x; }
function d(x, y) { return x && (y + 1); }
function e(x, y) { return x || (y - 2); }
function f(x) { return x - 0 + (0 + x); }
function g() { return (5 - 2) * 10 + (1 < 1) + (2 <= 2) * 100; }
function h(x) { return -(-x) + --x; }
// The sign of zero shows through a division: y + 0 is not y (-0 + 0 is +0); y + -0 and y - 0 are.
function z1(y) { return 1 / (y + 0); }
function z2(y) { return 1 / (0 + y); }
function z3(y) { return 1 / (y - -0); }
function z4(y) { return 1 / (y + -0); }
function z5(y) { return 1 / (y - 0); }
function zero(p) { return 0; }
function z6(y) { var v = 3e38 / (y += zero(y)); return v; }  // found by backend_diff: inlined, y + 0
// min and max keep their operands' order: of -0 and +0 they return the first, so GVN must not
// take min(y, -0) for min(-0, y) (found by backend_diff).
function z7(y) { var a = min(-0, y); var b = min(y, -0); return 1 / b + 0 * a; }
function z8(y) { var a = max(0, y); var b = max(y, 0); return 1 / b + 0 * a; }
// run: a(3) == -3
// run: b(4) == 0.25
// run: c(2) == 6
// run: d(1, 2) == 1
// run: d(1, -1) == 0
// run: d(0, 5) == 0
// run: e(0, 5) == 1
// run: e(0, 2) == 0
// run: e(3, 2) == 1
// run: f(2.5) == 5
// run: g() == 130
// run: h(4) == 7
// run: z1(-0) == inf
// run: z2(-0) == inf
// run: z3(-0) == inf
// run: z4(-0) == -inf
// run: z5(-0) == -inf
// run: z6(-0) == inf
// run: z6(0) == inf
// run: z7(0) == inf
// run: z7(-0) == -inf
// run: z8(-0) == -inf
// run: z8(0) == inf
