// sin and cos as the compiling backends inline them (runtime/math's batch algorithm step for
// step): every quadrant, both zero signs, the edge of the fast range and past it (where a group
// takes the batch function instead), NaN and the infinities, and a sin and cos of one value made
// together (one reduction for both) beside values that have only one of the two.
function s(x) { return sin(x); }
function c(x) { return cos(x); }
function pair(x) { return sin(x) * 2 + cos(x); }
function pairs(x, y) { var a = cos(x); var b = sin(y); return a * 1000 + sin(x) * cos(y) + b; }
function twice(x) { return sin(x) + sin(x * 3) + cos(x * 3) + cos(x); }
// run: s(1) ~= 0.841470957
// run: s(2) ~= 0.909297407
// run: s(4) ~= -0.756802499
// run: s(-2) ~= -0.909297407
// run: s(6) ~= -0.279415488
// run: c(3) ~= -0.989992499
// run: c(4) ~= -0.653643608
// run: c(-2) ~= -0.416146845
// run: c(0.785398) ~= 0.707106888
// run: s(0) == 0
// run: s(-0) == -0
// run: c(-0) == 1
// run: s(800000) ~= -0.282166213
// run: c(800000) ~= 0.959365547
// run: s(1000000) ~= -0.349993497
// run: c(1000000) ~= 0.936752141
// run: s(-123456.7) ~= 0.999415934
// run: s(nan) == nan
// run: c(inf) == nan
// run: s(-inf) == nan
// run: pair(1) ~= 2.22324419
// run: pair(1000000) ~= 0.236765146
// run: pair(nan) == nan
// run: pairs(1, 2) ~= 540.861389
// run: pairs(1000000, 1) ~= 937.404541
// run: twice(0.5) ~= 2.42524028
