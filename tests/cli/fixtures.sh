# Fixtures every CLI feature test may use (sourced after lib.sh): small scripts and scenes in $T,
# the paper's examples ($P), the backends this build has ($BACKENDS; $LLVM set when llvm is one).
P="$SRC/examples/paper"
BACKENDS="vm sse"
LLVM=""
if [ "${FS_HAVE_LLVM:-1}" = 1 ]; then
  BACKENDS="vm sse llvm"
  LLVM=1
fi
cat > "$T/sphere.fs" <<'FS'
function FRep(x, y, z, t) { return 1 - x*x - y*y - z*z; }
FS
cat > "$T/parts.fs" <<'FS'
x=u; y=v*2; z=-w;
FS
cat > "$T/bad.fs" <<'FS'
function f(x) {
  return x + ;
}
function g(y) { return h(y); }
FS
cat > "$T/loop.fs" <<'FS'
function f(x) {
  while (true) {
    x = x + 1;
  }
  return x;
}
FS
cat > "$T/rec.fs" <<'FS'
function f(x) { return f(x + 1); }
FS
cat > "$T/fact.fs" <<'FS'
function fact(n) { if (n <= 1) return 1; return n * fact(n - 1); }
FS
cat > "$T/nan.fs" <<'FS'
function f(x) { return sqrt(x) + log(x); }
FS
cat > "$T/scene.wrl" <<'WRL'
#VRML V2.0 utf8
FShape { geometry FGeometry {
  definition "function frep(x,y,z,t){
     return 1 - x*x - undefined_thing;
  }"
} }
WRL
printf 'function down(n) { if (n <= 0) return 0; return 1 + down(n - 1); }\n' > "$T/down.fs"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "0.5^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [8] } }\n' > "$T/ball.wrl"
printf '// a ball\nfunction FRep(x, y, z, t) {\n  return 0.8 - sqrt(x*x + y*y + z*z);\n}\n' > "$T/ball.fs"
