// Built-ins and their exact special cases.
function f_round(x) { return round(x); }
// Math.round keeps the sign of zero: -0 for x in [-0.5, 0], as node gives (the oracle found +0).
function f_round_zero(x) { return 1 / round(x); }
function f_round_folded() { return 1 / round(-0.4) + 1 / Math.round(-0.5) + 1 / round(-0); }
function f_round_positive() { return 1 / round(0.4); }
function f_floor(x) { return floor(x); }
function f_ceil(x) { return ceil(x); }
function f_sign(x) { return sign(x); }
function f_abs(x) { return abs(x) + fabs(x); }
function f_min(a, b) { return min(a, b); }
function f_max(a, b) { return max(a, b); }
function f_clamp(x) { return clamp(x, 0, 1); }
// Equal zeros: min and max return their first operand, so min(-0, min(y, -0)) is -0 at y = +0
// (LLVM 19 folded the nested selects to min(y, -0), +0; found by backend_diff).
function f_min_zeros(y) { return 1 / min(min(-0, -0), min(y, -0)); }
function f_max_zeros(y) { return 1 / max(max(0, 0), max(y, 0)); }
function f_pow(a, b) { return pow(a, b); }
function f_mod(a, b) { return mod(a, b); }
function f_sqrt(x) { return sqrt(x); }
function f_math(x) { return Math.max(x, Math.PI); }
function f_pi() { return pi; }
function f_sin(x) { return sin(x); }
// sin(-0) is -0 (the polynomial's r + (-0) gave +0 in every backend's batch code; the node oracle).
function f_sin_zero(x) { return 1 / sin(x) + 1 / sin(x * 2); }
function f_exp(x) { return exp(x); }
function f_log(x) { return log(x); }
function f_atan2(y, x) { return atan2(y, x); }
function f_noise(x, y, z) { return noise(x, y, z); }
// run: f_round(2.5) == 3
// run: f_round(-2.5) == -2
// run: f_round(0.49999997) == 0
// run: f_round(-0.5) == 0
// run: f_round(nan) == nan
// run: f_round_zero(-0.4) == -inf
// run: f_round_zero(-0.5) == -inf
// run: f_round_zero(-0) == -inf
// run: f_round_zero(0.49999997) == inf
// run: f_round_zero(-0.50000006) == -1
// run: f_round_zero(-1.5) == -1
// run: f_round_folded() == -inf
// run: f_round_positive() == inf
// run: f_floor(-1.5) == -2
// run: f_ceil(-1.5) == -1
// run: f_sign(-3) == -1
// run: f_sign(0) == 0
// run: f_sign(nan) == nan
// run: f_abs(-2) == 4
// run: f_min(1, nan) == nan
// run: f_min(nan, 1) == nan
// run: f_max(nan, 1) == nan
// run: f_max(1, nan) == nan
// run: f_max(-1, 2) == 2
// run: f_min_zeros(0) == -inf
// run: f_min_zeros(-0) == -inf
// run: f_max_zeros(-0) == inf
// run: f_max_zeros(0) == inf
// run: f_clamp(2) == 1
// run: f_clamp(-2) == 0
// run: f_clamp(nan) == nan
// run: f_pow(2, 0.5) ~= 1.41421354
// run: f_pow(1, nan) == nan
// run: f_pow(nan, 0) == 1
// run: f_pow(1, inf) == nan
// run: f_pow(-8, 1) == -8
// run: f_mod(-7, 2) == -1
// run: f_sqrt(-1) == nan
// run: f_sqrt(2) == 1.41421354
// run: f_math(1) == 3.14159274
// run: f_pi() == 3.14159274
// run: f_sin(0) == 0
// run: f_sin(1) ~= 0.841470957
// run: f_sin_zero(-0) == -inf
// run: f_sin_zero(0) == inf
// run: f_exp(1) ~= 2.71828175
// run: f_exp(100) == inf
// run: f_exp(-200) == 0
// run: f_log(0) == -inf
// run: f_log(-1) == nan
// run: f_log(1) == 0
// run: f_atan2(1, 1) ~= 0.785398185
// run: f_noise(0, 0, 0) == 0
// run: f_noise(inf, 0, 0) == nan
