// A user function may take a built-in's name: calls go to the user's function, and Math.NAME
// stays the built-in.
function sin(x) { return x * 2; }
function max(a, b) { return a - b; }
function f(x) { return sin(x); }
function g(x) { return Math.sin(x); }
function h(a, b) { return max(a, b) + Math.max(a, b); }
// run: f(3) == 6
// run: g(0) == 0
// run: g(1.5707964) == 1
// run: h(5, 2) == 8
