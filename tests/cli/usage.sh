#!/usr/bin/env bash
# Command lines a user gets wrong: an unknown option or command is named, with the nearest known
# one, exit status 2; what looks like an option but is a value ("-inf", "-1,1,-1,1") still works.
# usage: usage.sh FSCRIPT SOURCE_DIR FVRML_RUN
set -u
F="$1"
SRC="$2"
R="$3"
D="${4:-}"
. "$SRC/tests/cli/lib.sh"

printf 'function main(x) { return x; }\n' > "$T/id.fs"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "0.3^2 - x^2 - y^2 - z^2" bboxSize 1 1 1 resolution [8] } }\n' > "$T/ball.wrl"
check "fscript run: a misspelt option, not a number" 2 "^error: unknown option '--backnd' \(did you mean '--backend'\?\)" -- "$F" run "$T/id.fs" --backnd vm
check "fscript run: a misspelt option with =" 2 "unknown option '--bakend' \(did you mean '--backend'\?\)" -- "$F" run "$T/id.fs" --bakend=vm
check "fscript run: a misspelt short option" 2 "unknown option '-q'" -- "$F" run "$T/id.fs" -q
check "fscript: a misspelt command" 2 "^error: unknown command 'rn' \(did you mean 'run'\?\); the commands are run, eval, check" -- "$F" rn "$T/id.fs"
check "fscript: a command it does not know" 2 "^error: unknown command 'compile'; the commands are run, eval, check, probe, profile, emit-ir, emit-asm, fmt, repl, bench, render2d" -- "$F" compile "$T/id.fs"
check "fscript render2d: an option of another command" 2 "unknown option '--points' \(did you mean '--repeat'\?\)|unknown option '--points'" \
  -- "$F" render2d "$T/id.fs" --size 8 --bounds -1,1,-1,1 --points 4
check "fvrml-run: a misspelt option" 2 "^error: unknown option '--backnd' \(did you mean '--backend'\?\)" -- "$R" "$T/ball.wrl" --backnd vm -o "$T/b.ply"
check "fvrml-run: a misspelt flag" 2 "unknown option '--keep-goin' \(did you mean '--keep-going'\?\)" -- "$R" "$T/ball.wrl" --keep-goin -o "$T/b.ply"
[ -e "$T/b.ply" ] && fail "fvrml-run with a misspelt option wrote b.ply"
# Values that start with '-'.
check "fscript run -inf" 0 "^-inf$" -- "$F" run "$T/id.fs" -inf
check "fscript run -1e3" 0 "^-1000$" -- "$F" run "$T/id.fs" -1e3
check "fscript run -b vm -2.5" 0 "^-2.5$" -- "$F" run "$T/id.fs" -b vm -2.5
printf "function f(x, y) { return x - y; }\n" > "$T/xy.fs"
check "fscript render2d --bounds -1,1,-1,1" 0 "white pixels" -- "$F" render2d "$T/xy.fs" --size 8 --bounds -1,1,-1,1 -o "$T/id.png"
check "fvrml-run --view -30,20" 0 "wrote" -- "$R" "$T/ball.wrl" --view -30,20 --size 32 -o "$T/b.png"
check "options before the command" 0 "^3$" -- "$F" --max-seconds 5 run "$T/id.fs" 3
check "fscript --help still works" 0 "Subcommands:" -- "$F" --help
check "fscript run --help" 0 "--backend" -- "$F" run --help

# Messages that say what to do.
check "--resolution-scale -1: a short message" 2 "^--resolution-scale: wants a number above 0, got '-1'$" -- "$R" "$T/ball.wrl" --resolution-scale -1
grep -q '[0-9]\{40\}' "$T/out.txt" && fail "--resolution-scale -1 prints a huge number"
printf 'function f(u) { return 10u; }\n' > "$T/suffix.fs"
check "10u: did you mean 10*u" 1 "suffix.fs:1:26: error: invalid suffix on number \(did you mean 10\*u\?\)" -- "$F" check "$T/suffix.fs"
printf '#VRML V2.0 utf8\nFShape { appearance FAppearance { material FMaterial { diffuseColour "r=1;" } } }\n' > "$T/colour.wrl"
check "a misspelt VRML field: did you mean" 1 "colour.wrl:2:56: error: 'FMaterial' has no field 'diffuseColour' \(did you mean 'diffuseColor'\?\)" -- "$F" check "$T/colour.wrl"
check "fscript check on a terminal: the word that all went well" 0 "ok: 1 script, no errors" -- python3 "$SRC/tests/cli/tty_run.py" "$F" check "$T/id.fs"
check "fscript check of two files on a terminal" 0 "ok: 2 files, 2 scripts, no errors" -- python3 "$SRC/tests/cli/tty_run.py" "$F" check "$T/id.fs" "$T/ball.wrl"
check "fscript check on a pipe: silence" 0 "" -- "$F" check "$T/id.fs"
[ -s "$T/out.txt" ] && fail "fscript check on a pipe printed: $(cat "$T/out.txt")"
# An array index known to be out of range is a warning at check (it fails whenever it runs).
printf 'function f(x) { var a = [1, 2, 3]; var i = 5; return a[i] + a[2]; }\n' > "$T/index.fs"
check "check: a[i] with i known to be 5, of three elements" 0 "index.fs:1:54: warning: index 5 is out of range for array 'a' of 3 elements whenever this runs" -- "$F" check "$T/index.fs"
grep -q "1:62" "$T/out.txt" && fail "check warned about a[2], which is in range"
check "run: the same index fails" 1 "index 5 is out of range for array 'a' of 3 elements" -- "$F" run "$T/index.fs"
printf 'function f(x) { var a = new Array(4); a[3] = x; return a[round(x)]; }\n' > "$T/fine.fs"
check "check: indices in range or not known say nothing" 0 "" -- "$F" check "$T/fine.fs"
[ -s "$T/out.txt" ] && fail "check warned about fine.fs: $(cat "$T/out.txt")"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "\nfunction FRep(x,y,z,t) {\n  var k = [1, 2];\n  return k[2] - x;\n}" } }\n' > "$T/index.wrl"
check "check: the same inside a .wrl, at the scene's line" 0 "index.wrl:5:10: warning: index 2 is out of range for array 'k' of 2 elements" -- "$F" check "$T/index.wrl"

finish usage
