// Global value numbering shares equal pure values, commutative operands in either order.
function FRep(x, y, z, t) {
  var a = x * y + sin(x);
  var b = y * x + sin(x);
  if (z > 0) { return a + b + x * y; }
  return a - b;
}
// run: FRep(2, 3, 1, 0) ~= 19.8185959
// ir-after: inline,promote,gvn,dce
//   fn @kernel(4) -> 1 kernel {
//   b0:
//     v0 = param 0
//     v1 = param 1
//     v2 = param 2
//     br b2
//   b1:
//     v4 = phi [v13, b3], [v15, b4]
//     ret v4
//   b2:
//     v6 = fmul v0, v1 !3:13
//     v7 = sin v0 !3:19
//     v8 = fadd v6, v7 !3:17
//     v9 = const 0
//     v10 = fgt v2, v9 !5:9
//     cbr v10, b3, b4
//   b3:
//     v12 = fadd v8, v8 !5:25
//     v13 = fadd v12, v6 !5:29
//     br b1
//   b4:
//     v15 = fsub v8, v8 !6:12
//     br b1
//   }
