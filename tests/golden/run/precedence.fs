// Operator precedence and associativity, as the language table fixes them.
function neg_pow(x) { return -x^2; }          // -(x^2)
function pow_neg(x) { return 2^-x; }          // 2^(-x)
function pow_right(a, b, c) { return a^b^c; } // a^(b^c)
function starstar(a, b) { return a ** b; }
function union(a, b) { return a | b; }        // max
function inter(a, b) { return a & b; }        // min
function mixed(a, b, c) { return a | b & c; } // & binds tighter than |
function cmp_chain(a, b) { return a < b == 1; }
function arith(a, b, c) { return a + b * c - a / b % c; }
function logic(a, b) { return a || b && 0; }
function ternary(a) { return a > 0 ? 1 : a < 0 ? -1 : 0; }
function assign_chain(a) { var p; var q; p = q = a + 1; return p + q; }
function unary_mix(a) { return - -a + +a + !a; }
// run: neg_pow(3) == -9
// run: pow_neg(1) == 0.5
// run: pow_right(2, 3, 2) == 512
// run: starstar(2, 10) == 1024
// run: union(1, 2) == 2
// run: inter(1, 2) == 1
// run: mixed(5, 1, 2) == 5
// run: mixed(0, 1, 2) == 1
// run: cmp_chain(1, 2) == 1
// run: arith(7, 2, 3) == 12.5
// run: logic(0, 5) == 0
// run: logic(3, 0) == 1
// run: ternary(5) == 1
// run: ternary(-5) == -1
// run: ternary(0) == 0
// run: assign_chain(1) == 4
// run: unary_mix(2) == 4
// run: unary_mix(0) == 1
