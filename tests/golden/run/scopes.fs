// var is function-scoped (hoisted), let/const block-scoped, parameters shadow globals.
var x0 = 100;
function shadow(x0) { return x0; }
function hoist() { v = 5; var v; return v; }
function block_let() {
  let a = 1;
  { let a = 2; }
  return a;
}
function var_in_block() {
  { var q = 7; }
  return q;
}
function loop_let() {
  var s = 0;
  for (let i = 0; i < 3; i++) s += i;
  return s;
}
function reads_top() { return x0 + 1; }
// run: shadow(3) == 3
// run: hoist() == 5
// run: block_let() == 1
// run: var_in_block() == 7
// run: loop_let() == 3
// run: reads_top() == 101
