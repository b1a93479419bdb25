// Arrays: literals, new Array(n), rounding of indices, length, bounds errors.
function lit(i) { var a = [10, 20, 30]; return a[i]; }
function filled(n) { var a = new Array(n); var s = 0; for (var i = 0; i < a.length; i++) s += a[i]; return s; }
function squares(n) {
  var a = new Array(n);
  for (var i = 0; i < n; i++) a[i] = i * i;
  var s = 0;
  for (var k = 0; k < n; k++) s += a[k];
  return s;
}
function compound(i) { var a = [1, 2, 3]; a[i] += 10; a[i]++; return a[i]; }
var table = [5, 6, 7];
function global_table(i) { table[i] = table[i] * 2; return table[0] + table[1] + table[2]; }
function len() { var a = [1, 2, 3, 4]; return a.length; }
// run: lit(0) == 10
// run: lit(1.6) == 30
// run: lit(0.5) == 20
// run: lit(1.4) == 20
// run: lit(-0.4) == 10
// run: lit(3) error: out of range
// run: lit(-1) error: out of range
// run: lit(nan) error: out of range
// run: filled(5) == 0
// run: squares(5) == 30
// run: compound(1) == 13
// run: global_table(1) == 24
// run: len() == 4
// run: filled(-1) error: sizes must be whole numbers
function pick(i) { var table = new Array(3); table[1] = 5; return table[i]; }
function helper_pick(i) { return pick(i) + 1; }
// run: pick(1) == 5
// run: pick(3) error: index 3 is out of range for array 'table' of 3 elements
// run: helper_pick(-1) error: index -1 is out of range for array 'table' of 3 elements
