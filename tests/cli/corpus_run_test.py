#!/usr/bin/env python3
"""Every course file as a student has it, end to end: fvrml-run on every .wrl of the shared corpus
with the file's own settings (no resolution scaling) to each of .wrl, .glb, .ply and .png. Each run
exits 0 (the one BS-encrypted file: exit 1 with the clear refusal and nothing written); the VRML97
output is read back by our own parser (fscript check); every .glb passes the Khronos validator;
every PLY with triangles carries vertex normals; a scene made only of implicit shapes gives a
closed, oriented 2-manifold with no inside-out component (checked on the OBJ, which writes a vertex
split for its normals once); each PNG is a PNG; and `fscript fmt` formats its scripts into a scene
that checks, formats to itself and meshes to the same PLY bytes.

usage: corpus_run_test.py FVRML_RUN FSCRIPT FVRML_MESHDIFF SOURCE_DIR SHARED_DIR"""
import glob
import json
import os
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import skip as skip_rules  # noqa: E402

RUN, FSCRIPT, DIFF, SRC, SHARED = sys.argv[1:6]
FORMATS = ("wrl", "glb", "ply", "png", "obj")
failures = []


def run(cmd):
    return subprocess.run(cmd, capture_output=True, text=True, errors="replace", timeout=300)


def last_json(stderr):
    for line in reversed(stderr.strip().splitlines()):
        if line.startswith("{"):
            return json.loads(line)
    return None


def check_file(index, scene, tmp):
    """The failures of one corpus file, and its .glb outputs for the validator."""
    name = os.path.relpath(scene, SHARED)
    encrypted = open(scene, "rb").read(8).startswith(b"BSCRYPT")
    out, glbs, kinds = [], [], None
    for fmt in FORMATS:
        path = os.path.join(tmp, f"{index}.{fmt}")
        p = run([RUN, scene, "-o", path, "--stats"])
        if encrypted:
            if p.returncode != 1 or "encrypted" not in p.stderr or os.path.exists(path):
                out.append(f"{name} -> {fmt}: wanted the encrypted file's refusal, got exit {p.returncode}")
            continue
        if p.returncode != 0:
            errors = [line for line in p.stderr.splitlines() if "error" in line][:2]
            out.append(f"{name} -> {fmt}: exit {p.returncode}: {' | '.join(errors)}")
            continue
        stats = last_json(p.stderr)
        kinds = [s["kind"] for s in stats["shapes"]] if stats else kinds
        if not os.path.isfile(path) or os.path.getsize(path) == 0:
            out.append(f"{name} -> {fmt}: no output")
            continue
        if fmt == "wrl":
            back = run([FSCRIPT, "check", path])
            if back.returncode != 0:
                out.append(f"{name}: our VRML97 output does not read back: {back.stderr.strip()[:300]}")
        elif fmt == "glb":
            glbs.append(path)
        elif fmt == "png":
            if open(path, "rb").read(8) != b"\x89PNG\r\n\x1a\n":
                out.append(f"{name} -> png: not a PNG")
        elif fmt == "ply":
            t = json.loads(run([DIFF, path]).stdout)["a"]
            if t["triangles"] and not t["normals"]:
                out.append(f"{name} -> ply: no vertex normals")
        elif fmt == "obj" and kinds and all(k == "implicit" for k in kinds):
            # OBJ writes a vertex split for its normals once: the surface's own topology.
            t = json.loads(run([DIFF, path]).stdout)["a"]
            for key in ("watertight", "oriented", "manifold"):
                if not t[key]:
                    out.append(f"{name} -> obj: not {key} ({t})")
            if t["inverted_components"]:
                out.append(f"{name} -> obj: {t['inverted_components']} inside-out components ({t})")
    if not encrypted:
        out.extend(check_fmt(name, index, scene, tmp))
    return name, out, glbs


def check_fmt(name, index, scene, tmp):
    """fscript fmt on the scene: its scripts formatted, the rest kept; the result checks, formats to
    itself, and meshes to the same PLY bytes."""
    p = run([FSCRIPT, "fmt", scene])
    if p.returncode != 0:
        return [f"{name}: fscript fmt: exit {p.returncode}: {p.stderr.strip()[:300]}"]
    formatted = os.path.join(tmp, f"{index}.fmt.wrl")
    with open(formatted, "w") as f:
        f.write(p.stdout)
    out = []
    if run([FSCRIPT, "check", formatted]).returncode != 0:
        out.append(f"{name}: the formatted scene does not check")
    if run([FSCRIPT, "fmt", "--check", formatted]).returncode != 0:
        out.append(f"{name}: fscript fmt is not idempotent on it")
    ply = os.path.join(tmp, f"{index}.fmt.ply")
    q = run([RUN, formatted, "-o", ply, "--stats"])
    stats = last_json(q.stderr) or {}
    if q.returncode != 0:
        out.append(f"{name}: the formatted scene does not run: {q.stderr.strip()[-300:]}")
    elif not [m for m in stats.get("missing_inlines", []) if "not fetched" not in m["reason"]] and open(ply, "rb").read() != open(os.path.join(tmp, f"{index}.ply"), "rb").read():
        out.append(f"{name}: the formatted scene meshes to other bytes")
    return out


def main():
    if not os.path.isdir(os.path.join(SHARED, "corpus")):
        skip_rules.skip("corpus_run", f"no corpus in {SHARED}", failures)
        return
    scenes = sorted(glob.glob(os.path.join(SHARED, "corpus", "**", "*.wrl"), recursive=True))
    with tempfile.TemporaryDirectory() as tmp:
        with ThreadPoolExecutor(max_workers=2) as pool:
            results = list(pool.map(lambda a: check_file(a[0], a[1], tmp), enumerate(scenes)))
        glbs = []
        for name, out, files in results:
            failures.extend(out)
            glbs.extend(files)
            print(f"{'FAIL' if out else 'ok  '} {name}")
        validator = os.environ.get("GLTF_VALIDATOR_DIR", "")
        if subprocess.run(["sh", "-c", "command -v node"], capture_output=True).returncode == 0 and \
           os.path.isdir(os.path.join(validator, "gltf-validator")):
            p = run(["node", os.path.join(SRC, "tests", "clients", "gltf_validate.mjs"), *glbs])
            for line in p.stdout.splitlines():
                r = json.loads(line)
                if r["numErrors"] or r["numWarnings"]:
                    failures.append(f"gltf-validator: {r}")
            if p.returncode != 0 and not failures:
                failures.append(f"gltf-validator failed: {p.stderr[:300]}")
            print(f"gltf-validator: {len(glbs)} files")
        else:
            skip_rules.skip("corpus_run glTF validation", "the Khronos glTF validator is not installed "
                            f"in {validator or '?'} (./dev.sh test installs it with npm)", failures)
    print(f"{len(scenes)} corpus files, {len(FORMATS)} outputs each")


main()
for f in failures:
    print("FAIL", f)
sys.exit(1 if failures else 0)
