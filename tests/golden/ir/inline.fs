// Non-recursive calls are inlined; recursive ones stay calls.
function sq(v) { return v * v; }
function dist(x, y) { return sqrt(sq(x) + sq(y)); }
function fact(n) { if (n <= 1) return 1; return n * fact(n - 1); }
function FRep(x, y, z, t) { return dist(x, y) + fact(3); }
// run: FRep(3, 4, 0, 0) == 11
// ir-after: inline,promote,simplify,fold,dce
//   fn @fact(1) -> 1 recursive {
//   b0:
//     v0 = param 0
//     v1 = const 1
//     v2 = fle v0, v1 !4:26
//     cbr v2, b1, b2
//   b1:
//     v4 = const 1
//     ret v4
//   b2:
//     v6 = const 1
//     v7 = fsub v0, v6 !4:60
//     v8 = call @fact(v7) !4:53
//     v9 = fmul v0, v8 !4:51
//     ret v9
//   }
//   fn @kernel(4) -> 1 kernel {
//   b0:
//     v0 = const nan
//     v1 = param 0
//     v2 = param 1
//     v3 = param 2
//     v4 = param 3
//     v5 = fmul v1, v1 !2:27
//     v6 = fmul v2, v2 !2:27
//     v7 = fadd v5, v6 !3:41
//     v8 = sqrt v7 !3:30
//     v9 = const 3
//     gstore @x, v1
//     gstore @y, v2
//     gstore @z, v3
//     gstore @u, v1
//     gstore @v, v2
//     gstore @w, v3
//     gstore @t, v4
//     gstore @r, v0
//     gstore @g, v0
//     gstore @b, v0
//     v20 = call @fact(v9) !5:49
//     v21 = fadd v8, v20 !5:47
//     ret v21
//   }
