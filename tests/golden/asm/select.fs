// A comparison and a select: the if-converted form of a branch.
function FRep(x, y, z, t) { return x > 0 ? x * 2 : -y; }
