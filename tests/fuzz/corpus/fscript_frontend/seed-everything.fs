var g = 0; var tab = [1, 2, 3];
function r(n) { if (n <= 0) return 0; return 1 + r(n - 1); }
function FRep(x, y, z, t) {
  var a = new Array(4); var s = 0;
  for (var i = 0; i < 4; i++) { a[i] = sin(x * i) + noise(x, y, z); if (a[i] > 0.5) continue; s += a[i]; }
  while (s > 10) { s = s / 2; if (s < 1) break; }
  g += tab[1] + a.length; s = x > 0 ? s : -s;
  return (s && y) || clamp(hypot(x, y), 0, 1) + atan2(y, x) + pow(abs(z), 0.5) + r(3) + g % 3;
}
