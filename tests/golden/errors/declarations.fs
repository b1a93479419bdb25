// Parameters and block-scoped declarations: duplicates are errors, var may be repeated, an inner
// block may shadow.
function f(x, x) { return x; }  // error@15: duplicate parameter 'x'
function g(a, b, a) { return a + b; }  // error@18: duplicate parameter 'a'
function h(x) { let a = 1; let a = 2; return a; }  // error@32: redeclaration of 'a' in the same block
function k(x) { const c = 1; let c = 2; return c; }  // error@34: redeclaration of 'c' in the same block
function m(x) { let d = 1; { let d = 2; x = d; } var e = 1; var e = 2; return d + e + x; }
