// Unknown names, wrong arity, misuse of functions, constants and const.
function f(x) { return x + nowhere; }  // error: unknown name 'nowhere'
function g(x) { return foo(x); }  // error: unknown function 'foo'
function h(x) { return sin(x, 1); }  // error: 'sin' takes 1 argument but 2 were given
function k(x) { return f(); }  // error: 'f' takes 1 argument but 0 were given
function m(x) { pi = 3; return x; }  // error: cannot assign to the constant 'pi'
function n(x) { const c = 1; c = 2; return c; }  // error: declared const
function o(x) { return f + 1; }  // error: 'f' is a function
function p(x) { f = 2; return x; }  // error: cannot assign to the function 'f'
function q(x) { break; return x; }  // error: 'break' outside a loop
function f(y) { return y; }  // error: redefinition of function 'f'
return 3;  // error: 'return' outside a function
function Helper(x) { return x; }
function r(x) { return Math.helper(x); }  // error: unknown function 'helper'
