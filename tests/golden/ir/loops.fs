// A loop keeps its phis and its budget tick through the pipeline.
function FRep(x, y, z, t) {
  var s = 0;
  for (var i = 0; i < 4; i++) s = s + x;
  return s;
}
// run: FRep(1.5, 0, 0, 0) == 6
// ir-after: opt
//   fn @kernel(4) -> 1 kernel {
//   b0:
//     v0 = param 0
//     v1 = const 0
//     br b1
//   b1:
//     v3 = phi [v1, b0], [v11, b2]
//     v4 = phi [v1, b0], [v9, b2]
//     v5 = const 4
//     v6 = flt v3, v5 !4:21
//     cbr v6, b2, b3
//   b2:
//     tick !4:3
//     v9 = fadd v4, v0 !4:37
//     v10 = const 1
//     v11 = fadd v3, v10
//     br b1
//   b3:
//     ret v4
//   }
