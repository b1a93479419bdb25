#!/usr/bin/env bash
# fscript probe and the REPL's :probe and :bound: every variable at a point with the backends' bits
# (checked against `fscript eval` of the same expressions on every backend), each if's branch and
# each min's and max's side, intervals over a box that hold the values inside it, and bad input.
# usage: probe.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

cat > "$T/p.fs" <<'FS'
function ball(p, r) {
  var d = p * p;
  return r - d;
}
function FRep(x, y, z, t) {
  var a = sin(x) * 3;
  var b = a + y;
  if (b > 1) {
    b = b - 1;
  }
  var c = min(ball(x, 0.5), ball(z, 0.3));
  return max(b - z, c);
}
function A(x, y, z, t) { return sin(x) * 3; }
function B(x, y, z, t) { return sin(x) * 3 + y - 1; }
FS
check "probe: the value and every variable at a point" 0 \
  "^at x=0.5 y=0.200000003 z=0.100000001 t=0: 0.538276672$" -- "$F" probe "$T/p.fs" --at 0.5,0.2,0.1
"$F" probe "$T/p.fs" --at 0.5,0.2,0.1 > "$T/probe.txt"
want() {  # NAME LINE: the probe's listing holds LINE exactly
  n=$((n + 1))
  grep -qxF -- "$2" "$T/probe.txt" || { fail "$1: no line '$2'"; cat "$T/probe.txt"; }
}
want "a variable" "6:7 FRep  a = 1.43827665"
want "a variable assigned again, in the branch taken" "9:5 FRep  b = 0.638276696"
want "the branch an if takes" "8:3 FRep  if true"
want "a helper's arguments, its last call" "1:10 ball  p = 0.100000001 (argument)"
want "a min's side" "11:11 FRep  min(0.25, 0.290000021) takes the first (0.25)"
want "a max's side" "12:10 FRep  max(0.538276672, 0.25) takes the first (0.538276672)"
# The backends' bits: the probe's numbers are what `fscript eval` prints for the same expressions.
for b in vm sse llvm; do
  [ "$b" = llvm ] && [ "${FS_HAVE_LLVM:-1}" = 0 ] && continue
  n=$((n + 1))
  f=$(echo "0.5,0.2,0.1,0" | "$F" eval "$T/p.fs" -b "$b")
  a=$(echo "0.5,0.2,0.1,0" | "$F" eval "$T/p.fs" -b "$b" --entry A)
  bb=$(echo "0.5,0.2,0.1,0" | "$F" eval "$T/p.fs" -b "$b" --entry B)
  grep -qxF "at x=0.5 y=0.200000003 z=0.100000001 t=0: $f" "$T/probe.txt" && grep -qxF "6:7 FRep  a = $a" "$T/probe.txt" &&
    grep -qxF "9:5 FRep  b = $bb" "$T/probe.txt" || fail "probe: values differ from fscript eval on $b ($f, $a, $bb)"
done
"$F" probe "$T/p.fs" --at -0.5,0,0 > "$T/probe.txt"
want "the other branch" "8:3 FRep  if false"
want "not reached" "9:5 FRep  b = nan (or not reached)"

# Over a box: intervals, decided choices, and every value at a point inside within its interval.
check "probe --bound: the value's interval" 0 "^over x in \[0, 0.100000001\] .*: \[0.289999992, 0.3995004\]$" \
  -- "$F" probe "$T/p.fs" --bound 0,0.1,0,0.1,0,0.1
"$F" probe "$T/p.fs" --bound 0,0.1,0,0.1,0,0.1 > "$T/probe.txt"
want "an if decided over the box" "8:3 FRep  if always false"
want "a min decided over the box" "11:11 FRep  min([0.48999998, 0.5], [0.289999992, 0.300000012]) always the second"
want "a max not decided" "12:10 FRep  max([-0.100000001, 0.3995004], [0.289999992, 0.300000012]) either"
want "a branch never taken" "9:5 FRep  b not reached (or NaN)"
"$F" probe "$T/p.fs" --at 0.03,0.07,0.05 > "$T/point.txt"
n=$((n + 1))
python3 - "$T/probe.txt" "$T/point.txt" <<'PY' || fail "probe: a value at a point of the box outside its interval"
import re, sys
box = {m.group(1): (float(m.group(2)), float(m.group(3)))
       for m in re.finditer(r"^(\S+ \S+  \w+) in \[(\S+), (\S+)\]", open(sys.argv[1]).read(), re.M)}
vals = {m.group(1): float(m.group(2)) for m in re.finditer(r"^(\S+ \S+  \w+) = (\S+)", open(sys.argv[2]).read(), re.M)}
bad = [k for k in box if k in vals and not box[k][0] <= vals[k] <= box[k][1]]
print(bad) if bad else None
sys.exit(1 if bad or len(set(box) & set(vals)) < 8 else 0)
PY

# The REPL on the last :load-ed script.
check "repl :probe" 0 "6:7 FRep  a = 1.43827665" -- bash -c "printf ':load $T/p.fs\n:probe 0.5 0.2 0.1\n' | '$F' repl"
check "repl :bound" 0 "8:3 FRep  if always false" -- bash -c "printf ':load $T/p.fs\n:bound 0 0.1 0 0.1 0 0.1\n' | '$F' repl"
check "repl :probe before :load" 0 "error: :load a .fs script first" -- bash -c "printf ':probe 1 2 3\n' | '$F' repl"
check "repl :probe with too few numbers" 0 "error: :probe X Y Z \[T\]" -- bash -c "printf ':load $T/p.fs\n:probe 1\n' | '$F' repl"

# Bad input.
printf 'function FRep(x, y, z, t) {\n  var s = 0;\n  for (var i = 0; i < x * 10; i++) { s = s + i; }\n  return s - y;\n}\n' > "$T/loop.fs"
check "probe of a loop at a point" 0 "3:38 FRep  s = 10" -- "$F" probe "$T/loop.fs" --at 0.45,0,0
check "probe --bound of a loop: intervals cannot bound it" 1 "intervals cannot bound it" -- "$F" probe "$T/loop.fs" --bound 0,1,0,1,0,1
check "probe needs --at or --bound" 2 "needs --at" -- "$F" probe "$T/p.fs"
check "probe: not a number" 2 "--at: 'zz' is not a number" -- "$F" probe "$T/p.fs" --at 1,zz,3
check "probe --bound: pairs" 2 "--bound takes pairs" -- "$F" probe "$T/p.fs" --bound 0,1,0
check "probe: a script error at its place" 1 "bad.fs:2:14: error" -- bash -c "printf 'function FRep(x, y, z, t) {\n  return 1 - qq;\n}\n' > '$T/bad.fs'; '$F' probe '$T/bad.fs' --at 0,0,0"
check "probe of a scene is refused" 1 "" -- "$F" probe "$SRC/examples/paper/figure1-morphing.wrl" --at 0,0,0
finish probe
