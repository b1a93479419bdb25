// Every syntax error of the file in one run, one diagnostic per mistake.
function a(x) {
  return x + ;  // error: expected an expression
}
function b(x) {
  var y = (x + 1;  // error: expected ')' to match
  return y;
}
function c(x) {
  if x > 0 return 1;  // error: expected '(' after 'if'
  return 0;
}
function d(x) {
  return x x;  // error: expected ';' after statement
}
function e(x) {
  return x # 2;  // error: '#' is not a comment
}
function f(1) { return 0; }  // error: expected a parameter name
var 5 = 3;  // error: expected a variable name
