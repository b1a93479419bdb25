function Foo(x) { return x; }
function main(x) { return Math.foo(x); }
