#!/usr/bin/env python3
"""The README's examples, run as written: every ```sh block that shows what a command prints (a
`# ...` comment after it) is run with the build's tools and the shared folder, and must print that;
the REPL session (the block of `fs>` lines) is typed into fscript under a pseudo-terminal and every
value it shows must come back in order. (The two set-up commands at the top are what CI runs.)
usage: readme_test.py SOURCE_DIR BUILD_DIR SHARED_DIR"""
import os
import pty
import re
import subprocess
import sys
import tempfile

from ptyread import read_until

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import skip as skip_rules  # noqa: E402

SRC, BUILD, SHARED = sys.argv[1], os.path.abspath(sys.argv[2]), os.path.abspath(sys.argv[3])
readme = open(os.path.join(SRC, "README.md")).read()
failures, checked = [], 0


def fenced_blocks(text):
    """(language, body) of every ``` block, read fence by fence."""
    blocks, lang, body = [], None, []
    for line in text.splitlines():
        if line.startswith("```"):
            if lang is None:
                lang, body = line[3:].strip(), []
            else:
                blocks.append((lang, "\n".join(body) + "\n"))
                lang = None
        elif lang is not None:
            body.append(line)
    return blocks


def skip(name, why):
    """A visible skip (tests/support/skip.py)."""
    skip_rules.skip(name, why, failures)


def run_commented_blocks(tmp):
    """```sh blocks whose command ends in `# WHAT IT PRINTS`."""
    global checked
    for block in [b for lang, b in fenced_blocks(readme) if lang == "sh"]:
        text = block.replace("\\\n", " ")
        for line in text.splitlines():
            m = re.match(r"^(build/\S+.*?)\s+#\s+(.+)$", line)
            if not m:
                continue
            cmd, want = m.group(1), m.group(2).strip()
            cmd = cmd.replace("build/", BUILD + "/", 1).replace("../shared", SHARED)
            if "../shared" in m.group(1) and not os.path.isdir(SHARED):
                skip(f"readme example `{m.group(1)}`", "the shared folder is absent: " + SHARED)
                continue
            checked += 1
            r = subprocess.run(cmd, shell=True, cwd=tmp, capture_output=True, text=True, timeout=300)
            out = r.stdout + r.stderr
            if r.returncode != 0 or want not in out:
                failures.append(f"README example `{m.group(1)}` should print '{want}'; exit {r.returncode}:\n{out[-800:]}")



def run_repl_session():
    """The README's `fs>` block: inputs after the prompts, the other lines the values it shows."""
    global checked
    blocks = [b for lang, b in fenced_blocks(readme) if not lang and b.startswith("fs> ")]
    if not blocks:
        failures.append("the README has no REPL session (a ``` block of fs> lines)")
        return
    pid, fd = pty.fork()
    if pid == 0:
        os.execve(os.path.join(BUILD, "tools/fscript/fscript"), ["fscript"],
                  dict(os.environ, TERM="xterm", FSCRIPT_HISTORY=os.devnull))
    read_until(fd, r"fs> $")
    screen = ""
    expected = []
    for line in blocks[0].splitlines():
        if line.startswith("fs> ") or line.startswith("... "):
            os.write(fd, (line[4:] + "\r").encode())
            screen += read_until(fd, r"(fs|\.\.\.)> $")
        elif line.strip():
            expected.append(line.strip())
    os.write(fd, b"\x15\x04")
    read_until(fd, r"$^", timeout=2)
    try:
        os.waitpid(pid, 0)
    except ChildProcessError:
        pass
    at = 0
    for want in expected:  # each value shown, in order, on a line of its own
        checked += 1
        m = re.compile(r"\r\n" + re.escape(want) + r"\r\n").search(screen, at)
        if not m:
            failures.append(f"the README's REPL session should show {want!r}; the screen was:\n{screen[-1500:]}")
            return
        at = m.end() - 2


with tempfile.TemporaryDirectory() as tmp:
    run_commented_blocks(tmp)
    run_repl_session()
for f in failures:
    print("FAIL " + f)
print(f"readme: {checked - len(failures)} of {checked} README examples as written")
sys.exit(1 if failures or checked < (3 if os.path.isdir(SHARED) else 2) else 0)
