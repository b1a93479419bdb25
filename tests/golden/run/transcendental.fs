// The transcendental built-ins the other cases do not call, each within the language's 4 ulp on
// every backend, before and after optimisation (folded calls use the scalar definitions, the
// backends the batch twins); their special values where JavaScript's Math fixes them.
function f_tan(x) { return tan(x); }
function f_asin(x) { return asin(x); }
function f_acos(x) { return acos(x); }
function f_atan(x) { return atan(x); }
function f_sinh(x) { return sinh(x); }
function f_cosh(x) { return cosh(x); }
function f_tanh(x) { return tanh(x); }
function f_log10(x) { return log10(x); }
function zero_signs(x) { return 1 / tan(x) + 1 / asin(x) + 1 / atan(x) + 1 / sinh(x) + 1 / tanh(x); }
function folded() { return log10(1000) + acos(1) + Math.cosh(0); }
// run: f_tan(1) ~= 1.55740774
// run: f_asin(0.5) ~= 0.523598790
// run: f_acos(0.5) ~= 1.04719758
// run: f_atan(1) ~= 0.785398185
// run: f_sinh(1) ~= 1.17520118
// run: f_cosh(1) ~= 1.54308069
// run: f_tanh(0.5) ~= 0.462117165
// run: f_log10(1000) == 3
// run: f_asin(2) == nan
// run: f_acos(-1.5) == nan
// run: f_atan(inf) ~= 1.57079637
// run: f_tanh(-inf) == -1
// run: f_cosh(-inf) == inf
// run: f_log10(0) == -inf
// run: f_log10(-1) == nan
// run: zero_signs(-0) == -inf
// run: zero_signs(0) == inf
// run: folded() == 4
