// Warnings: letter-case slips (the program still runs), maybe-unassigned locals, missing returns.
function FRep(x, y, z, t) {
  var r0 = 0.5 * Pi;  // warning: 'Pi' is not defined; using 'pi'
  return r0 - X;  // warning: 'X' is not defined; using 'x'
}
function maybe(c) {
  var a;
  if (c > 0) a = 1;
  return a;  // warning: 'a' may be used before it is assigned
}
function partial(c) {  // warning: 'partial' can reach its end without 'return'
  if (c > 0) return 1;
}
function Slip(x) { return Sin(x); }  // warning: 'Sin' is not defined; using 'sin'
// run: FRep(0, 0, 0, 0) ~= 1.57079637
// run: maybe(1) == 1
// run: maybe(-1) == nan
// run: partial(-1) == nan
// run: Slip(0) == 0
