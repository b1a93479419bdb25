// A loop: four lanes under masks, the budget tick, the phi moves on the back edge.
function FRep(x, y, z, t) {
  var s = 0;
  for (var i = 0; i < 3; i++) s = s + x;
  return s;
}
