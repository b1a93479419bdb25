// User functions, recursion, globals shared between functions.
function sq(x) { return x * x; }
function hyp(a, b) { return sqrt(sq(a) + sq(b)); }
function fact(n) { if (n <= 1) return 1; return n * fact(n - 1); }
function fib(n) { return n < 2 ? n : fib(n - 1) + fib(n - 2); }
function even(n) { if (n == 0) return 1; return odd(n - 1); }
function odd(n) { if (n == 0) return 0; return even(n - 1); }
var counter = 10;
function bump() { counter = counter + 1; return counter; }
function twice() { bump(); return bump(); }
function set_global(v) { implicit_g = v; return 0; }
function read_global(v) { set_global(v); return implicit_g * 2; }
function no_return(x) { if (x > 0) return 1; }  // warning: can reach its end
// run: hyp(3, 4) == 5
// run: fact(10) == 3628800
// run: fib(15) == 610
// run: even(10) == 1
// run: odd(7) == 1
// run: twice() == 12
// run: read_global(21) == 42
// run: no_return(1) == 1
// run: no_return(-1) == nan
