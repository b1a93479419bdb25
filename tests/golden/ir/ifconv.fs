// Small branches of pure code become selects.
function FRep(x, y, z, t) {
  var d;
  if (x > 0) d = x * 2; else d = -x;
  var e = y;
  if (y < 0) e = 0;
  return d + e;
}
// run: FRep(2, -1, 0, 0) == 4
// run: FRep(-3, 5, 0, 0) == 8
// ir-after: opt
//   fn @kernel(4) -> 1 kernel {
//   b0:
//     v0 = param 0
//     v1 = param 1
//     v2 = const 0
//     v3 = fgt v0, v2 !4:9
//     v4 = const 2
//     v5 = fmul v0, v4 !4:20
//     v6 = fneg v0 !4:34
//     v7 = select v3, v5, v6
//     v8 = flt v1, v2 !6:9
//     v9 = select v8, v2, v1
//     v10 = fadd v7, v9 !7:12
//     ret v10
//   }
