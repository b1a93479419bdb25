#!/usr/bin/env bash
# `--format`: the format named, whatever the file is called; binary STL's layout.
# usage: formats.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

# ---- --format: the format named, whatever the file is called ----
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "0.5^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [8] } }\n' > "$T/ball.wrl"
for fm in ply:ply obj:'v ' wrl:'#VRML V2.0 utf8' glb:glTF png:PNG; do
  check "--format ${fm%%:*}" 0 '' -- "$R" "$T/ball.wrl" -o "$T/ball.out" --format "${fm%%:*}"
  head -c 64 "$T/ball.out" | tr -d '\000' | grep -qa -- "${fm#*:}" || fail "--format ${fm%%:*} did not write ${fm%%:*}"
done
# Binary STL: an 80-byte header, the triangle count, 50 bytes per triangle.
check "--format stl" 0 '' -- "$R" "$T/ball.wrl" -o "$T/ball.out" --format stl
python3 -c "
import struct, sys
d = open(sys.argv[1], 'rb').read()
sys.exit(0 if len(d) > 84 and len(d) == 84 + 50 * struct.unpack('<I', d[80:84])[0] else 1)" "$T/ball.out" ||
  fail "--format stl did not write binary STL"
check "--format unknown" 2 "format" -- "$R" "$T/ball.wrl" -o "$T/ball.out" --format dxf

finish formats
