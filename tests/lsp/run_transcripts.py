#!/usr/bin/env python3
"""Runs LSP transcript files against fscript-lsp: each `--> JSON` line is sent framed, each `==> TEXT`
line sent as raw bytes (escapes like \\r\\n resolved, for malformed frames), each `<-- JSON` line is
the next message the server must send, matched against what it gives (objects: the keys given; lists:
the same number of items, each matched by a different item, in any order, or, when the first item is
"...", at least the items given; strings starting with "re:" are regular expressions), `exit N` is
the status the server must end with once its input closes. A message the transcript does not expect,
even after its last line, is a failure. usage: run_transcripts.py FSCRIPT_LSP FILES..."""
import json
import re
import subprocess
import sys
import threading
import queue

LSP = sys.argv[1]


def matches(want, got):
    if isinstance(want, dict):
        return isinstance(got, dict) and all(k in got and matches(v, got[k]) for k, v in want.items())
    if isinstance(want, list) and all(not isinstance(w, (dict, list)) for w in want):
        return want == got  # a list of plain values (semantic token data): exactly, in order
    if isinstance(want, list):
        if not isinstance(got, list):
            return False
        at_least = bool(want) and want[0] == "..."
        want = want[1:] if at_least else want
        return (len(got) >= len(want) if at_least else len(got) == len(want)) and one_to_one(want, got)
    if isinstance(want, str) and want.startswith("re:"):
        return isinstance(got, str) and re.search(want[3:], got) is not None
    return want == got


def one_to_one(want, got):
    """Each item of `want` matched by a different item of `got` (a small bipartite search)."""
    taken = [False] * len(got)

    def place(i):
        if i == len(want):
            return True
        for j, g in enumerate(got):
            if not taken[j] and matches(want[i], g):
                taken[j] = True
                if place(i + 1):
                    return True
                taken[j] = False
        return False

    return place(0)


def reader(stream, out):
    while True:
        headers = {}
        while True:
            line = stream.readline()
            if not line:
                out.put(None)
                return
            line = line.decode().rstrip("\r\n")
            if not line:
                break
            k, _, v = line.partition(":")
            headers[k.strip().lower()] = v.strip()
        body = stream.read(int(headers["content-length"]))
        out.put(json.loads(body))


def run(path):
    proc = subprocess.Popen([LSP], stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    replies = queue.Queue()
    threading.Thread(target=reader, args=(proc.stdout, replies), daemon=True).start()
    failures = []
    want_exit = None
    for number, line in enumerate(open(path, encoding="utf-8"), 1):
        line = line.rstrip("\n")
        if line.startswith("-->"):
            body = json.dumps(json.loads(line[3:])).encode()
            proc.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
            proc.stdin.flush()
        elif line.startswith("==>"):
            proc.stdin.write(line[4:].encode().decode("unicode_escape").encode("latin-1"))
            proc.stdin.flush()
        elif line.startswith("<--"):
            want = json.loads(line[3:])
            try:
                got = replies.get(timeout=20)
            except queue.Empty:
                got = "(nothing within 20 s)"
            if not matches(want, got):
                failures.append(f"{path}:{number}: wanted {json.dumps(want)}\n  got {json.dumps(got)[:2000]}")
        elif line.startswith("exit "):
            want_exit = int(line[5:])
    proc.stdin.close()
    try:
        status = proc.wait(timeout=20)
    except subprocess.TimeoutExpired:
        proc.kill()
        failures.append(f"{path}: the server did not end when its input closed")
        status = None
    if want_exit is not None and status != want_exit:
        failures.append(f"{path}: exit status {status}, wanted {want_exit}")
    while True:  # everything the server sent that no `<--` line asked for
        try:
            extra = replies.get(timeout=2)
        except queue.Empty:
            break
        if extra is None:
            break
        failures.append(f"{path}: a message the transcript does not expect: {json.dumps(extra)[:500]}")
    return failures


all_failures = []
for path in sys.argv[2:]:
    all_failures += run(path)
for f in all_failures:
    print("FAIL " + f)
print(f"{len(sys.argv) - 2 - len(set(f.split(':')[0] for f in all_failures))} of {len(sys.argv) - 2} transcripts passed")
sys.exit(1 if all_failures else 0)
