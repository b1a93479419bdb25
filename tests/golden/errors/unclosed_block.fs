function f(x) {  // error: unterminated block
  if (x > 0) {
    return 1;
  }
