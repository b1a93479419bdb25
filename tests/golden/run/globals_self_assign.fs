// A global assigned its own value, then read by a recursive callee: the value the kernel set must
// be in memory at the call (promotion once took `acc = acc` for proof that memory held it).
var acc = 0;
function keep() { acc = acc; return acc; }
function rec(n) { if (n <= 0) return acc; acc = acc + 1; return rec(n - 1); }
function FRep(x, y, z, t) { keep(); return acc + rec(2); }
function G(x) { acc = x; acc = acc; return rec(1) + acc; }
// run: FRep(0, 0, 0, 0) == 2
// run: G(5) == 12
