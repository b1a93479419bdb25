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
