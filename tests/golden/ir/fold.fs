// Constant folding goes through runtime/math, so folded values equal run-time ones.
function FRep(x, y, z, t) {
  var k = 6.283185307179586 * 2.0;
  var a = sin(0.5) + sqrt(2) * k;
  return x * 1 + a - 0 + (1 < 2) * y;
}
// run: FRep(0, 0, 0, 0) ~= 18.2509575
// ir-after: inline,promote,fold,dce
//   fn @kernel(4) -> 1 kernel {
//   b0:
//     v0 = param 0
//     v1 = param 1
//     br b2
//   b1:
//     ret v6
//   b2:
//     v4 = const 18.2509575 !4:20
//     v5 = fadd v0, v4 !5:16
//     v6 = fadd v5, v1 !5:24
//     br b1
//   }
