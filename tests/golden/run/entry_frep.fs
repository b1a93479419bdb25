// FRep is found without regard to case; x, y, z are also globals, and so are u, v, w.
function frep(x1, y1, z1, t) {
  x = x1; y = y1; z = z1;
  return 1 - x*x - y*y - z*z + t + u - x1;
}
// run: $(0, 0, 0, 0) == 1
// run: $(1, 0, 0, 0) == 0
// run: $(0, 0, 0, 2) == 3
