// Arithmetic, min with the NaN rule and a square root: the straight-line core of every shape.
function FRep(x, y, z, t) { return min(x, y) - sqrt(z * z + 1); }
