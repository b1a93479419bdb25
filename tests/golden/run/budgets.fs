// Loop, recursion and array budgets stop runaway scripts with an error naming the budget.
// flags: max-loop=1000 max-depth=50 max-array=100
function forever() { var i = 0; while (true) { i++; } return i; }
function deep(n) { return deep(n + 1); }
function big() { var a = new Array(1000); return a[0]; }
function ok_loop() { var s = 0; for (var i = 0; i < 500; i++) s++; return s; }
function ok_depth(n) { if (n <= 0) return 0; return 1 + ok_depth(n - 1); }
// run: forever() error: loop iteration budget exceeded
// run: deep(0) error: call depth budget exceeded
// run: big() error: sizes must be whole numbers from 0 to the budget of 100
// run: ok_loop() == 500
// run: ok_depth(40) == 40
function chain3(x) { return chain2(x) + 1; }
function chain2(x) { return chain1(x) + 1; }
function chain1(x) { return x; }
// Non-recursive calls never count against the depth budget, optimised (inlined) or not.
// run: chain3(1) == 3
