#!/usr/bin/env python3
"""The layering rule, checked at build time: a folder includes only itself and the folders below it.

Usage: check_layers.py SOURCE_ROOT [--stamp FILE]. Prints "file:line: error: ..." for every
include that points up (or sideways into a layer it may not see) and exits 1; on success writes
the stamp file (the build's proof that the check ran). The table is docs/architecture.md's
"Layers" drawn as data; a new top-level component must be added here before it builds.
"""
import os
import re
import sys

BOTTOM = ["runtime/support", "runtime/math"]
# component -> the components it may include (besides itself). Longest prefix names a file's component.
ALLOWED = {
    "runtime/support": [],
    "runtime/math": ["runtime/support"],
    "ir": BOTTOM,
    "ir/passes": ["ir"] + BOTTOM,
    "frontend": ["ir"] + BOTTOM,
    "backends": ["ir", "ir/passes"] + BOTTOM,
    "engine/driver": ["frontend", "ir", "ir/passes", "backends"] + BOTTOM,
    "engine/mesh": ["backends", "ir"] + BOTTOM,
    "engine/render": ["engine/mesh", "backends", "ir"] + BOTTOM,
    "engine/scene": ["engine/driver", "engine/mesh", "engine/render", "frontend", "backends", "ir"] + BOTTOM,
    "lsp": ["engine/scene", "frontend", "ir"] + BOTTOM,
}
# The top: executables, tests and benchmarks may include anything.
TOP = ["tools", "tests", "bench"]
SOURCE_DIRS = ["runtime", "ir", "frontend", "backends", "engine", "lsp"]
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def component(path):
    best = None
    for c in ALLOWED:
        if (path == c or path.startswith(c + "/")) and (best is None or len(c) > len(best)):
            best = c
    return best


def check(root):
    errors = []
    for top in SOURCE_DIRS:
        for dirpath, _, names in os.walk(os.path.join(root, top)):
            for name in sorted(names):
                if not name.endswith((".h", ".cpp", ".def")):
                    continue
                rel = os.path.relpath(os.path.join(dirpath, name), root)
                if any(rel == t or rel.startswith(t + "/") for t in TOP):
                    continue
                here = component(rel)
                if here is None:
                    errors.append(f"{rel}:1: error: no layer for this file: add its folder to tests/support/check_layers.py")
                    continue
                with open(os.path.join(root, rel), encoding="utf-8", errors="replace") as f:
                    for n, line in enumerate(f, 1):
                        m = INCLUDE.match(line)
                        if not m or "/" not in m.group(1):
                            continue  # a generated or system-style header, not a component's
                        target = component(m.group(1))
                        if target is None:
                            if m.group(1).split("/")[0] in ("tools", "tests", "bench"):
                                errors.append(f"{rel}:{n}: error: {here} includes {m.group(1)}, which is the top layer")
                            continue
                        if target != here and target not in ALLOWED[here]:
                            may = ", ".join(ALLOWED[here]) or "nothing below it"
                            errors.append(f"{rel}:{n}: error: {here} includes {m.group(1)} ({target}); "
                                          f"{here} may include only {may}")
    return errors


def main(argv):
    if len(argv) < 2:
        print("usage: check_layers.py SOURCE_ROOT [--stamp FILE]", file=sys.stderr)
        return 2
    errors = check(argv[1])
    for e in errors:
        print(e, file=sys.stderr)
    if errors:
        print(f"check_layers: {len(errors)} include(s) against the layering (docs/architecture.md, Layers)",
              file=sys.stderr)
        return 1
    if "--stamp" in argv:
        with open(argv[argv.index("--stamp") + 1], "w") as f:
            f.write("layers ok\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
