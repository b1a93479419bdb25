// Arrays are storage, not values.
function takes(a) { return a; }
function f() { var a = [1, 2]; return takes(a); }  // error: arrays cannot be passed
function g() { var a = [1, 2]; return a; }  // error: arrays cannot be returned
function h() { var a = [1, 2]; return a + 1; }  // error: 'a' is an array
function k() { var s = 1; return s[0]; }  // error: 's' is not an array
function m() { var s = 1; s = [1]; return s; }  // error: an array literal can only initialize an array variable
function n() { var a = [1]; a = 3; return a[0]; }  // error: cannot assign a number to the array 'a'
function o() { return nothing[0]; }  // error: unknown array 'nothing'
