// Postfix ++ and -- belong to the line of their operand: `a \n ++b` is `a; ++b`.
function f(x) {
  var a = x
  a
  ++x
  return a * 10 + x
}
function g(x) {
  var a = x
  a++
  return a
}
function h(x) {
  var a = x
  var b = a
  --a
  return b * 10 + a
}
// run: f(3) == 34
// run: g(3) == 4
// run: h(5) == 54
