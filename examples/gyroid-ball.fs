// A gyroid cut by a ball: smooth sheets with a sharp seam where they meet the ball, and thin
// bridges along it that dual contouring keeps as marching tetrahedra does
// (fvrml-run examples/gyroid-ball.fs --mesher mt|dc -o gyroid.png).
function FRep(x, y, z, t) {
  var k = 1;
  var g = sin(k * x) * cos(k * y) + sin(k * y) * cos(k * z) + sin(k * z) * cos(k * x);
  return min(g, 16 - x * x - y * y - z * z);
}
