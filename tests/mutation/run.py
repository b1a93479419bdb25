#!/usr/bin/env python3
"""Mutation testing: applies each mutant of tests/mutation/mutants.txt, one at a time, to a copy of the
tree, rebuilds, runs the tests the mutant names and reports which mutants survived (the tests stayed
green). usage: run.py [--work DIR] [--only ID,ID...] [--report FILE]

mutants.txt, one mutant per block (blank lines between blocks, '#' lines are comments):
    id: time-end-boundary
    file: engine/scene/time_model.cpp
    find: if (end <= 0) return s;
    replace: if (end < 0) return s;
    tests: unit_time_model|cli
    why: (optional) what the mutant stands for; `equivalent: REASON` marks a known equivalent mutant
`find` must occur exactly once in the file (a mutant never lands somewhere unintended)."""
import argparse
import os
import re
import shutil
import subprocess
import sys
import time

SRC = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def load(path):
    mutants, cur = [], {}
    for line in open(path, encoding="utf-8"):
        line = line.rstrip("\n")
        if line.startswith("#"):
            continue
        if not line.strip():
            if cur:
                mutants.append(cur)
            cur = {}
            continue
        key, _, value = line.partition(": ")
        if key not in ("id", "file", "find", "replace", "tests", "why", "equivalent"):
            sys.exit(f"{path}: unknown key in line {line!r}")
        cur[key] = value.replace("\\n", "\n")
    if cur:
        mutants.append(cur)
    for m in mutants:
        for key in ("id", "file", "find", "replace", "tests"):
            if key not in m:
                sys.exit(f"{path}: mutant {m.get('id', '?')} has no '{key}'")
    return mutants


def all_found(tree, mutants):
    """Every mutant's text is in its file exactly once (else it would land nowhere or somewhere unintended)."""
    ok = True
    for m in mutants:
        path = os.path.join(tree, m["file"])
        text = open(path, encoding="utf-8").read() if os.path.exists(path) else ""
        if text.count(m["find"]) != 1:
            print(f"BAD MUTANT {m['id']}: its text occurs {text.count(m['find'])} times in {m['file']}")
            ok = False
    return ok


def tests_exist(build, mutants):
    """Every test pattern a mutant names matches a ctest test (a renamed test would kill nothing)."""
    listing = subprocess.run(["ctest", "--test-dir", build, "-N"], capture_output=True, text=True).stdout
    names = re.findall(r"Test +#\d+: (\S+)", listing)
    ok = True
    for m in mutants:
        for pattern in m["tests"].split("|"):
            if not any(re.search(pattern, n) for n in names):
                print(f"BAD MUTANT {m['id']}: no test matches '{pattern}'")
                ok = False
    return ok


def sh(cmd, cwd, log, timeout=None):
    with open(log, "a") as f:
        f.write(f"$ {' '.join(cmd)}\n")
        f.flush()
        try:
            return subprocess.run(cmd, cwd=cwd, stdout=f, stderr=subprocess.STDOUT, timeout=timeout).returncode
        except subprocess.TimeoutExpired:
            f.write("(timed out)\n")
            return 124


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--work", default="/tmp/fvrml-mutation")
    ap.add_argument("--only", default="")
    ap.add_argument("--report", default="")
    ap.add_argument("--check", action="store_true", help="only check that every mutant's text is there once")
    ap.add_argument("--build", default="", help="with --check: the build whose ctest names the mutants' tests must match")
    args = ap.parse_args()
    mutants = load(os.path.join(SRC, "tests", "mutation", "mutants.txt"))
    if args.check:  # a ctest: a refactor or a reformat that moves a mutant's text fails here, not months later
        ok = all_found(SRC, mutants)
        if args.build:
            ok = tests_exist(args.build, mutants) and ok
        sys.exit(0 if ok else 1)
    if args.only:
        keep = set(args.only.split(","))
        mutants = [m for m in mutants if m["id"] in keep]
    # The build inside the copy, as build/ is inside the checkout: with CCACHE_BASEDIR above both,
    # ccache sees the same relative paths and the copy's first build comes from the cache.
    tree, log = os.path.join(args.work, "tree"), os.path.join(args.work, "log.txt")
    build = os.path.join(tree, "build")
    os.environ.setdefault("CCACHE_BASEDIR", os.path.commonpath([os.path.realpath(SRC), os.path.realpath(args.work)]))
    os.makedirs(args.work, exist_ok=True)
    open(log, "w").close()
    # A copy of the tracked files (the working tree's versions), so the checkout is never touched.
    files = subprocess.run(["git", "ls-files", "-z"], cwd=SRC, capture_output=True, check=True).stdout.decode().split("\0")
    for rel in filter(None, files):
        dst = os.path.join(tree, rel)
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        if not os.path.exists(dst) or open(os.path.join(SRC, rel), "rb").read() != open(dst, "rb").read():
            shutil.copy(os.path.join(SRC, rel), dst)  # a fresh mtime: copy2 kept the source's, older than the last build's objects, and ninja kept them stale
    shared = os.environ.get("FVRML_SHARED", os.path.join(os.path.dirname(SRC), "shared"))
    cfg = ["cmake", "-S", tree, "-B", build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release", f"-DFS_SHARED_DIR={shared}"]
    if sh(cfg, tree, log) or sh(["ninja", "-C", build], tree, log):
        sys.exit(f"the unmutated tree does not build; see {log}")
    if not all_found(tree, mutants):
        sys.exit(1)
    # Every test a mutant names must pass on the unmutated tree, or a "kill" would mean nothing.
    every = "|".join(sorted({t for m in mutants for t in m["tests"].split("|")}))
    if sh(["ctest", "--test-dir", build, "-j", "2", "-R", every, "--timeout", "300"], tree, log, timeout=3600):
        sys.exit(f"the tests fail on the unmutated tree; see {log}")
    results = []
    for k, m in enumerate(mutants, 1):
        path = os.path.join(tree, m["file"])
        original = open(path, encoding="utf-8").read()
        open(path, "w", encoding="utf-8").write(original.replace(m["find"], m["replace"], 1))
        start = time.time()
        if sh(["ninja", "-C", build], tree, log):
            verdict = "does not build"
        else:
            status = sh(["ctest", "--test-dir", build, "-j", "2", "-R", m["tests"], "--timeout", "300"], tree, log, timeout=1800)
            verdict = "killed" if status else ("equivalent" if "equivalent" in m else "SURVIVED")
        open(path, "w", encoding="utf-8").write(original)
        results.append((m, verdict, time.time() - start))
        print(f"[{k}/{len(mutants)}] {m['id']}: {verdict} ({time.time() - start:.0f} s)", flush=True)
    sh(["ninja", "-C", build], tree, log)  # back to the unmutated build
    killed = sum(1 for _, v, _ in results if v == "killed")
    equivalent = sum(1 for _, v, _ in results if v == "equivalent")
    stillborn = sum(1 for _, v, _ in results if v == "does not build")
    scored = len(results) - stillborn - equivalent
    lines = [f"{killed} of {scored} mutants killed ({100.0 * killed / max(1, scored):.1f}%); "
             f"{equivalent} documented as equivalent, {stillborn} did not build", "",
             "| mutant | file | verdict | tests run |", "|---|---|---|---|"]
    for m, v, _ in results:
        lines.append(f"| {m['id']} | {m['file']} | {v} | {m['tests']} |")
    report = "\n".join(lines) + "\n"
    print(report)
    if args.report:
        open(args.report, "w").write(report)
    sys.exit(0 if killed == scored else 1)


if __name__ == "__main__":
    main()
