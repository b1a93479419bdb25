#!/usr/bin/env bash
# Shapes by their results: pattern colours (piecewise linear, clamped), Figure 6's blends (one
# closed surface, bigger than the union), mirroring Transforms (faces kept outward).
# usage: shapes.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

# ---- Colours through patternKey / patternColor: piecewise linear in the value, clamped ----
printf '#VRML V2.0 utf8\nFShape { appearance FAppearance { material FMaterial { diffuseColor "x" patternKey [-0.5 0 0.5] patternColor [1 0 0, 0 1 0, 0 0 1] } }\n geometry FGeometry { definition "0.8^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [12] } }\n' > "$T/pattern.wrl"
"$R" "$T/pattern.wrl" -o "$T/pattern-out.wrl" 2> /dev/null
jcheck "patternKey/patternColor: every vertex coloured by its x" out "
len(j['points']) > 100 and all(len(p) == 6 for p in j['points']) and all(
  max(abs(a - b) for a, b in zip(p[3:], [min(1, max(0, -2 * p[0])), max(0, 1 - 2 * abs(p[0])), min(1, max(0, 2 * p[0]))])) < 2e-3
  for p in j['points'])
" -- python3 "$SRC/tests/clients/mesh_probe.py" "$T/pattern-out.wrl" --vertices

# ---- Blends: Figure 6's blended spheres are one closed surface, bigger than the plain union ----
"$R" "$P/figure6-blends.wrl" --fraction 0.5 -o "$T/f6.obj" --resolution-scale 0.4 2> /dev/null
jcheck "Figure 6: the blend is closed, oriented and 2-manifold" out "
all(j['a'][k] for k in ('watertight', 'oriented', 'manifold')) and j['a']['euler'] % 2 == 0
" -- "$D" "$T/f6.obj" "$T/f6.obj"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "function frep(x,y,z,t){ var f = 0.3^2-(x-0.35)^2-y^2-z^2; var g = 0.3^2-(x+0.35)^2-y^2-z^2; return BODY; }" bboxSize 2 2 2 resolution [48] } }\n' > "$T/blend.tpl"
sed 's|BODY|max(f, g)|' "$T/blend.tpl" > "$T/union.wrl"
sed 's|BODY|f + g + sqrt(f*f + g*g) + 0.02 / (1 + (f/0.1)^2 + (g/0.1)^2)|' "$T/blend.tpl" > "$T/blend.wrl"
"$R" "$T/union.wrl" -o "$T/union.obj" 2> /dev/null
"$R" "$T/blend.wrl" -o "$T/blend.obj" 2> /dev/null
python3 - "$SRC/tests/clients/mesh_probe.py" "$T" <<'PY' || fail "a blend union: one body, more volume than the plain union, less than its box"
import json, math, subprocess, sys
probe, d = sys.argv[1], sys.argv[2]
vol = lambda n: json.loads(subprocess.run([sys.executable, probe, f"{d}/{n}.obj"], capture_output=True, text=True, check=True).stdout)["volume"]
u, b = vol("union"), vol("blend")
spheres = 2 * 4 / 3 * math.pi * 0.3 ** 3
print(u, b, spheres)
sys.exit(0 if abs(u - spheres) < 0.03 * spheres and spheres * 1.02 < b < spheres * 2 else 1)
PY
n=$((n + 1))

# ---- A mirroring Transform keeps faces outward (the winding flips with the matrix) ----
for s in "1 1 1" "-1 1 1" "-1 -1 -1" "1 -2 1"; do
  printf '#VRML V2.0 utf8\nTransform { scale %s children FShape { geometry FGeometry { definition "0.5^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [16] } } }\n' "$s" > "$T/mirror.wrl"
  "$R" "$T/mirror.wrl" -o "$T/mirror.obj" 2> /dev/null
  jcheck "scale $s: faces outward (positive volume)" out "j['volume'] > 0.9 * 4 / 3 * 3.14159 * 0.125 * abs($(tr ' ' '*' <<< "$s"))" \
    -- python3 "$SRC/tests/clients/mesh_probe.py" "$T/mirror.obj"
done

finish shapes
