#!/usr/bin/env python3
"""Checks the editor files: the TextMate grammars and VS Code manifests parse as JSON, every regex
compiles, and the FScript grammar and the Vim syntax file name every keyword and built-in of the
compiler's own tables (frontend/fscript/tokens.def, builtins.def), so highlighting cannot drift
from the language; with Neovim installed, the Vim files are loaded by a real Neovim and a .fs file
and the scripts inside a .wrl are highlighted as FScript.
usage: check_grammars.py SOURCE_DIR"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

src = sys.argv[1]
failures = []
docs = {}
for name in ["vscode/package.json", "vscode/language-configuration.json", "vscode/syntaxes/fscript.tmLanguage.json",
             "vscode/syntaxes/vrml.tmLanguage.json"]:
    try:
        docs[name] = json.load(open(f"{src}/editors/{name}"))
    except Exception as e:
        failures.append(f"{name}: {e}")


def regexes(node):
    if isinstance(node, dict):
        for k, v in node.items():
            if k in ("match", "begin", "end") and isinstance(v, str):
                yield v
            else:
                yield from regexes(v)
    elif isinstance(node, list):
        for v in node:
            yield from regexes(v)


for name, doc in docs.items():
    for rx in regexes(doc):
        try:
            re.compile(rx.replace("(?=", "(?="))
        except re.error as e:
            failures.append(f"{name}: bad regex {rx!r}: {e}")
grammar = json.dumps(docs.get("vscode/syntaxes/fscript.tmLanguage.json", {}))
tokens = open(f"{src}/frontend/fscript/tokens.def").read()
builtins = open(f"{src}/frontend/fscript/builtins.def").read()
for word in re.findall(r'FS_KEYWORD\(\w+, "(\w+)"\)', tokens) + re.findall(r'^FS_BUILTIN\("(\w+)"', builtins, re.M):
    if not re.search(r"[(|]" + word + r"[|)]", grammar):
        failures.append(f"fscript.tmLanguage.json does not name '{word}'")
vim_syntax = open(f"{src}/editors/vim/syntax/fscript.vim").read()
vim_words = set()
for line in vim_syntax.splitlines():
    m = re.match(r"syntax keyword \w+ (.*)", line)
    if m:
        vim_words.update(m.group(1).split())
for word in re.findall(r'^FS_KEYWORD\(\w+, "(\w+)"\)', tokens, re.M) + re.findall(r'^FS_BUILTIN\("(\w+)"', builtins, re.M):
    if word not in vim_words:
        failures.append(f"editors/vim/syntax/fscript.vim does not name '{word}'")


def nvim_highlights(path, positions):
    """The syntax group names Neovim gives (line, column) positions of `path`, with editors/vim on
    its runtimepath as the README says to set it up."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "syn.txt")
        probes = ", ".join(f'synIDattr(synID({l},{c},1),"name")' for l, c in positions)
        cmd = ["nvim", "--headless", "-u", "NONE", "-i", "NONE", "--cmd", f"set rtp^={src}/editors/vim",
               "--cmd", f"set rtp+={src}/editors/vim/after", "-c", "filetype on", "-c", "syntax on", "-c", f"e {path}",
               "-c", f"call writefile([&filetype, {probes}], '{out}')", "-c", "qa!"]
        subprocess.run(cmd, timeout=60, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        return open(out).read().split("\n")[:len(positions) + 1] if os.path.exists(out) else []


if shutil.which("nvim"):
    with tempfile.TemporaryDirectory() as tmp:
        fs = os.path.join(tmp, "ball.fs")
        open(fs, "w").write("// a ball\nfunction FRep(x, y, z, t) {\n  return 0.8 - sqrt(x * x + y * y + z * z);\n}\n")
        got = nvim_highlights(fs, [(1, 1), (2, 1), (3, 3), (3, 16), (3, 10)])
        want = ["fscript", "fscriptComment", "fscriptKeyword", "fscriptKeyword", "fscriptBuiltin", "fscriptNumber"]
        if got != want:
            failures.append(f"Neovim highlights a .fs file as {got}, wanted {want}")
        wrl = os.path.join(tmp, "s.wrl")
        open(wrl, "w").write('#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "\n'
                             'function FRep(x, y, z, t) { return 0.8 - sqrt(x*x); }" } }\n'
                             'Shape { geometry Text { string "sqrt" } }\n')
        got = nvim_highlights(wrl, [(3, 1), (3, 42), (4, 32)])
        want = ["vrml", "fscriptKeyword", "fscriptBuiltin", "VRMLString"]
        if got != want:
            failures.append(f"Neovim highlights a .wrl's script and plain strings as {got}, wanted {want}")
else:
    print("note: nvim is not installed; the Vim files were checked by their word lists only")
for f in failures:
    print("FAIL " + f)
print("editor files: " + ("ok" if not failures else f"{len(failures)} problems"))
sys.exit(1 if failures else 0)
