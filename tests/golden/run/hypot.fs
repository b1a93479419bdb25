// hypot(x, y): the length of (x, y) without overflow or underflow; +inf when either is infinite,
// even with a NaN (Math.hypot). On every backend, before and after optimisation.
function h(x, y) { return hypot(x, y); }
function ring(x, y) { return 1 - hypot(x, y); }
function folded() { return hypot(6, 8) + Math.hypot(-5, 12); }
// run: h(3, 4) == 5
// run: h(-3, -4) == 5
// run: h(3e30, 4e30) == 5e30
// run: h(3e-30, 4e-30) == 5e-30
// run: h(inf, nan) == inf
// run: h(nan, -inf) == inf
// run: h(nan, 2) == nan
// run: h(0, -0) == 0
// run: ring(0.6, 0.8) == 0
// run: ring(0, 0.5) == 0.5
// run: folded() == 23
