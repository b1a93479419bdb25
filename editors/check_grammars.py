#!/usr/bin/env python3
"""Checks the editor files: the TextMate grammars and VS Code manifests parse as JSON, every regex
compiles, and the FScript grammar names every keyword and built-in of the compiler's own tables
(frontend/fscript/tokens.def, builtins.def), so highlighting cannot drift from the language.
usage: check_grammars.py SOURCE_DIR"""
import json
import re
import sys

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
for f in failures:
    print("FAIL " + f)
print("editor files: " + ("ok" if not failures else f"{len(failures)} problems"))
sys.exit(1 if failures else 0)
