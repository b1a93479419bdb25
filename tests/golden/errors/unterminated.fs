function f(x) { return x; }
/* this comment never ends  // error: unterminated comment
function g(x) { return x; }
