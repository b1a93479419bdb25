// Globals become SSA values in the kernel; a recursive callee keeps them in memory.
var acc = 0;
function add(v) { acc = acc + v; return acc; }
function rec(n) { if (n <= 0) return acc; acc = acc + 1; return rec(n - 1); }
function FRep(x, y, z, t) { add(x); add(y); return acc + rec(2); }
// run: FRep(1, 2, 0, 0) == 8
// ir-after: inline,promote,fold,simplify,dce
//   fn @rec(1) -> 1 recursive {
//   b0:
//     v0 = gload @acc
//     v1 = param 0
//     v2 = const 0
//     v3 = fle v1, v2 !4:25
//     cbr v3, b1, b2
//   b1:
//     ret v0
//   b2:
//     v6 = const 1
//     v7 = fadd v0, v6 !4:53
//     v8 = const 1
//     v9 = fsub v1, v8 !4:71
//     gstore @acc, v7
//     v11 = call @rec(v9) !4:65
//     ret v11
//   }
//   fn @kernel(4) -> 1 kernel {
//   b0:
//     v0 = const nan
//     v1 = param 0
//     v2 = param 1
//     v3 = param 2
//     v4 = param 3
//     v5 = const 0
//     v6 = fadd v5, v1 !3:29
//     v7 = fadd v6, v2 !3:29
//     v8 = const 2
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
//     gstore @acc, v7
//     v20 = call @rec(v8) !5:58
//     v21 = fadd v7, v20 !5:56
//     ret v21
//   }
