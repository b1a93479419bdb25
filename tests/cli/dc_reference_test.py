#!/usr/bin/env python3
"""Dual contouring against a dense reference (issue 16), with fvrml-meshdiff: every example and
corpus file with implicit shapes is meshed at half its resolution by dual contouring and by
marching tetrahedra, and by marching tetrahedra at three times that (the reference). Dual
contouring must keep marching tetrahedra's topology (Euler characteristic, closed or not,
manifold and oriented), and be no farther from the reference (Hausdorff) than 1.25 times marching
tetrahedra's distance.

usage: dc_reference_test.py FVRML_RUN FVRML_MESHDIFF SOURCE_DIR SHARED_DIR"""
import glob
import json
import os
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import skip as skip_rules  # noqa: E402

RUN, DIFF, SRC, SHARED = sys.argv[1:5]
SCALE, REFERENCE = "0.5", "1.5"
SLACK = 1.25  # dual contouring's Hausdorff distance may be this much of marching tetrahedra's
failures = []


def skip(name, why):
    """A visible skip (tests/support/skip.py)."""
    skip_rules.skip(name, why, failures)


def mesh(scene, out, *args):
    """fvrml-run's --stats, or None when the scene cannot be read (an encrypted corpus file)."""
    p = subprocess.run([RUN, scene, "-o", out, "--stats", *args], capture_output=True, text=True, errors="replace")
    return json.loads(p.stderr.strip().splitlines()[-1]) if p.returncode == 0 else None


def distance(reference, other):
    p = subprocess.run([DIFF, reference, other], capture_output=True, text=True, check=True)
    return json.loads(p.stdout)


def check(scene):
    """The failures for one scene (none when it has no implicit shape)."""
    name = os.path.relpath(scene, SHARED) if scene.startswith(SHARED) else os.path.relpath(scene, SRC)
    with tempfile.TemporaryDirectory() as tmp:
        # OBJ: a vertex dual contouring splits for its normals is one point of it there (PLY and glTF
        # hold the copies apart).
        dc, mt, ref = (os.path.join(tmp, f + ".obj") for f in ("dc", "mt", "ref"))
        stats = mesh(scene, dc, "--mesher", "dc", "--resolution-scale", SCALE)
        if stats is None or stats["dual_contouring"]["shapes"] == 0:
            return name, None, []
        if mesh(scene, mt, "--mesher", "mt", "--resolution-scale", SCALE) is None or \
           mesh(scene, ref, "--mesher", "mt", "--resolution-scale", REFERENCE) is None:
            return name, None, [f"{name}: marching tetrahedra failed"]
        d, m = distance(ref, dc), distance(ref, mt)
    out = []
    for key in ("euler", "watertight"):
        if d["b"][key] != m["b"][key]:
            out.append(f"{name}: {key} {d['b'][key]} by dual contouring, {m['b'][key]} by marching tetrahedra")
    for key in ("manifold", "oriented"):  # not when the scene's other shapes are open sheets crossing it
        if m["b"][key] and not d["b"][key]:
            out.append(f"{name}: the dual contouring mesh is not {key}, the marching tetrahedra one is")
    if d["hausdorff_relative"] > SLACK * m["hausdorff_relative"]:
        out.append(f"{name}: Hausdorff distance to the reference {d['hausdorff_relative']:.5f} of the box "
                   f"(marching tetrahedra {m['hausdorff_relative']:.5f})")
    line = (f"{name}: Hausdorff {d['hausdorff_relative']:.5f} (mt {m['hausdorff_relative']:.5f}), triangles "
            f"{d['b']['triangles']} (mt {m['b']['triangles']}), Euler {d['b']['euler']}")
    return name, line, out


scenes = sorted(glob.glob(os.path.join(SRC, "examples", "*.fs")) + glob.glob(os.path.join(SRC, "examples", "paper", "*.wrl")))
if os.path.isdir(os.path.join(SHARED, "corpus")):
    scenes += sorted(glob.glob(os.path.join(SHARED, "corpus", "**", "*.wrl"), recursive=True))
else:
    skip("dc_reference corpus", "the shared corpus is absent: " + os.path.join(SHARED, "corpus"))
checked = 0
with ThreadPoolExecutor(max_workers=2) as pool:
    for name, line, out in pool.map(check, scenes):
        if line:
            checked += 1
            print(line)
        failures += out
if checked < 3:
    failures.append(f"only {checked} scenes with implicit shapes were found")
for f in failures:
    print("FAIL", f)
print(f"dual contouring against dense references: {checked} scenes, {len(failures)} failures")
sys.exit(1 if failures else 0)
