function FRep(x, y, z, t) {
  var s = "abc;
  for (var i = 0; i < 1e9; i++ { s += [1, 2,
