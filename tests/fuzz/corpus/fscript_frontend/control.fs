// if/else, loops, break and continue.
function absval(x) { if (x < 0) { return -x; } else { return x; } }
function sum_to(n) {
  var s = 0;
  for (var i = 1; i <= n; i++) s += i;
  return s;
}
function first_square_above(n) {
  var i = 0;
  while (true) {
    if (i * i > n) break;
    i++;
  }
  return i;
}
function odd_sum(n) {
  var s = 0;
  for (var i = 0; i < n; i = i + 1) {
    if (i % 2 == 0) continue;
    s = s + i;
  }
  return s;
}
function do_once(n) {
  var c = 0;
  do { c++; } while (c < n);
  return c;
}
function nested(n) {
  var c = 0;
  for (var i = 0; i < n; i++)
    for (var j = 0; j < n; j++) {
      if (j > i) break;
      c += 1;
    }
  return c;
}
function countdown(n) {
  var k = n;
  while (k > 0) k -= 1;
  return k;
}
function nan_is_false(x) { if (x) return 1; else return 0; }
// run: absval(-3) == 3
// run: absval(4) == 4
// run: sum_to(100) == 5050
// run: first_square_above(50) == 8
// run: odd_sum(10) == 25
// run: do_once(0) == 1
// run: do_once(5) == 5
// run: nested(4) == 10
// run: countdown(7) == 0
// run: nan_is_false(nan) == 0
// run: nan_is_false(-0) == 0
// run: nan_is_false(0.5) == 1
