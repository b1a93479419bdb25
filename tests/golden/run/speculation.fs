// Straight code as the compiling backends speculate on it (the wasm emitter's straight_block):
// the inputs within a bound under which the value ranges drop NaN tests, the second operands of
// min, max and clamp not NaN, trig arguments in the fast range, truthiness without NaN. Each run
// breaks one guess (a NaN, an infinity or a huge input; a NaN made inside from ordinary inputs;
// sin of a large argument), and the batch mixes them with lanes that keep every guess, so a group
// that takes the exact code again must give the same bits as one that does not.
function m(x, y) { return min(x, sqrt(y)) + max(y, sqrt(x)); }
function z(x, y) { return min(x, y * 0) - max(0, x * y); }
function cl(x, y) { return clamp(x, sqrt(y), 2 - y); }
function tr(x, y) { return sin(x * 5) * y + cos(y) + (x ? 1 : 2); }
function big(x, y) { return sin(x * x * x) + y; }
function mix(x, y) { var d = sqrt(x * x + y * y) - 1; return max(min(d, sin(y * 1000)), -sqrt(1 - x)); }
// run: m(1, 4) == 5
// run: m(1, -4) == nan
// run: m(-1, 4) == nan
// run: m(0.25, 0.25) == 0.75
// run: z(1, 2) == -2
// run: z(1, inf) == nan
// run: z(-1, nan) == nan
// run: z(1e30, 1e-30) == -1
// run: cl(3, 1) == 1
// run: cl(0.5, 4) == -2
// run: cl(1, -1) == nan
// run: cl(nan, 1) == nan
// run: cl(-inf, 1) == 1
// run: z(1, -inf) == nan
// run: tr(0.5, 2) ~= 1.78079748
// run: tr(0, 1) ~= 2.54030228
// run: tr(nan, 1) == nan
// run: tr(200000, 1) ~= 1.19030881
// run: tr(1, 1e30) ~= -9.58924342e+29
// run: big(60000, 0) ~= 0.573299289
// run: big(0.5, 1) ~= 1.12467468
// run: big(-61234.5, 2) ~= 1.07806993
// run: mix(0.5, 0.5) ~= -0.467771798
// run: mix(2, 0.5) == nan
// run: mix(0.1, 900) ~= 0.316282034
// run: mix(-inf, 1) ~= 0.826879501
