// More kinds of syntax errors, each reported once, all in one run.
function a(x) { return max(x, 1; }  // error: expected ')' to close the argument list
function b(x) { var q = [1, 2; return x; }  // error: expected ']' to close the array literal
function c(x) { for (var i = 0; i < 3) x++; return x; }  // error: expected ';' after the condition of 'for'
function d(x) { 1 = x; return x; }  // error: the left side of '=' cannot be assigned to
function e(x) { return ++1; }  // error: '++' needs a variable or array element
function f(x) { return x.size; }  // error: unknown property 'size'
function g(x) { var z = new Thing(3); return x; }  // error: expected 'Array' after 'new'
function h(x) { return "text"; }  // error: expected an expression
function k(x) { return x ? 1; }  // error: expected ':' in conditional expression
function m(x) { else { return x; } }  // error: expected an expression
function n(x) { return 3x; }  // error: invalid suffix on number
function o(x) { return x; } }  // error: unexpected '}'
function p(x) { function inner() { return 1; } return x; }  // error: functions can only be declared at the top level
function q(x) { const k; return x; }  // error: 'const' declaration of 'k' needs a value
