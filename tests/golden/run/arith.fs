// IEEE float32 arithmetic: results are rounded to float at every step.
function add(a, b) { return a + b; }
function sub(a, b) { return a - b; }
function mul(a, b) { return a * b; }
function div(a, b) { return a / b; }
function rem(a, b) { return a % b; }
function third() { return 1 / 3; }
function big() { return 16777216 + 1; }       // 2^24 + 1 is not a float: rounds to 2^24
function tenth() { return 0.1 + 0.2; }
// run: add(1, 2) == 3
// run: sub(1, 3) == -2
// run: mul(1.5, 4) == 6
// run: div(1, 4) == 0.25
// run: div(1, 0) == inf
// run: div(-1, 0) == -inf
// run: div(0, 0) == nan
// run: rem(7, 3) == 1
// run: rem(-7, 3) == -1
// run: rem(7, -3) == 1
// run: rem(5.5, 2) == 1.5
// run: rem(1, 0) == nan
// run: third() == 0.333333343
// run: big() == 16777216
// run: tenth() == 0.300000012
// run: add(inf, -inf) == nan
// run: mul(0, inf) == nan
