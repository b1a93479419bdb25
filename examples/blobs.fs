// A 2D slice of a function-defined solid: three blended discs minus a hole, cut by a wave.
// fscript render2d examples/blobs.fs --size 800x600 --bounds -2,2,-1.5,1.5 -o out/blobs.png
function disc(x, y, cx, cy, r) { return r*r - (x - cx)^2 - (y - cy)^2; }

// Pasko-Savchenko blended union (the paper's "addblend").
function blend(f1, f2, a0, a1, a2) {
  var fa1 = f1 / a1;
  var fa2 = f2 / a2;
  return f1 + f2 + sqrt(f1*f1 + f2*f2) + a0 / (1 + fa1*fa1 + fa2*fa2);
}

function FRep(x, y, z, t) {
  var body = blend(disc(x, y, -0.7, 0, 0.6), disc(x, y, 0.7, 0.1, 0.5), 0.3, 0.5, 0.5);
  body = blend(body, disc(x, y, 0, 0.8, 0.45), 0.3, 0.5, 0.5);
  var hole = disc(x, y, 0, 0.1, 0.25);
  var wave = y + 0.45 + 0.12 * sin(8 * x);
  return min(min(body, -hole), wave);
}
