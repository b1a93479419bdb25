// A cube turned off the grid axes with a ball bitten out of one corner: sharp CSG edges, the case
// that tells the meshers apart (fvrml-run examples/csg.fs --mesher mt|dc -o csg.png).
function FRep(x, y, z, t) {
  var a = 0.8 * x + 0.6 * y, b = -0.6 * x + 0.8 * y;
  var cube = 3 - max(max(abs(a), abs(b)), abs(z));
  var dx = a - 3, dy = b - 3, dz = z - 3;
  var ball = sqrt(dx * dx + dy * dy + dz * dz) - 3.5;
  return min(cube, ball);
}
