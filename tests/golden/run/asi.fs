// Automatic semicolons at line breaks; a missing ';' before '}' or at the end is fine.
function f(a) {
  var b = a
  var c = b
  - 1
  return c
}
function g(a) { return a }
var k = 3
function h() { return k }
// run: f(5) == 4
// run: g(2) == 2
// run: h() == 3
