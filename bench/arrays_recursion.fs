// Arrays and recursion per point: the VM's lane-by-lane paths (array ops, calls), for regression checks.
function f(n) { if (n <= 1) return n; return f(n - 1) + f(n - 2); }
function FRep(x, y, z, t) {
  var a = new Array(8);
  for (var i = 0; i < 8; i++) a[i] = x * i + y;
  var s = 0;
  for (var i = 0; i < 8; i++) s = s + a[i] * a[7 - i];
  return s + f(6) - z;
}
