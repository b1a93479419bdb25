#!/usr/bin/env python3
"""A new built-in cannot be missed silently. Every list that must name each built-in (or each op)
is checked against the tables: the fuzz dictionaries, the built-in list of docs/language.md, a
golden case per built-in, an interval rule per op with a function in ir/opcodes.def, a batch twin per Batch or
Trig row. And the recipe of docs/architecture.md ("Adding an operation") must name every file that
names `hypot`, the last built-in added whole, so the recipe is the list a new built-in really
needs. (The editor grammars are checked by editors/check_grammars.py, the switches by the build.)
usage: builtins_check.py SOURCE_DIR"""
import os
import re
import subprocess
import sys

src = sys.argv[1]
failures = []


def read(rel):
    with open(os.path.join(src, rel), encoding="utf-8") as f:
        return f.read()


builtins = re.findall(r'^FS_BUILTIN\("(\w+)",\s*(\d+),\s*(\w+)', read("frontend/fscript/builtins.def"), re.M)
# FS_OP(Name, "mnemonic", arity, flags, function, how): the math rows are those with a `how`.
op_rows = re.findall(r'^FS_OP\((\w+),\s*"([\w.]+)",\s*(-?\d+),\s*[^,]+,\s*(\w+),\s*(\w+)\)',
                     read("ir/opcodes.def"), re.M)
ops = [(op, mnemonic) for op, mnemonic, _, _, _ in op_rows]
op_arity = dict((op, int(arity)) for op, _, arity, _, _ in op_rows)
math_rows = [(op, fn, arity, how) for op, _, arity, fn, how in op_rows if how != "None"]
batch_rows = dict((n, int(a)) for n, a in re.findall(r'^FS_BATCH_FN\((\w+),\s*(\d+)\)',
                                                    read("runtime/math/batch_functions.def"), re.M))
if not builtins or not ops or not math_rows:
    sys.exit("builtins_check: could not read the tables")

# Each built-in names an op of its arity.
for name, arity, op in builtins:
    if op_arity.get(op) != int(arity):
        failures.append(f"frontend/fscript/builtins.def: '{name}' takes {arity} arguments but ir/opcodes.def's {op} "
                        f"takes {op_arity.get(op)}")

# The fuzz dictionaries: every built-in's name, every op's mnemonic.
fscript_dict, ir_dict = read("tests/fuzz/dict/fscript.dict"), read("tests/fuzz/dict/ir.dict")
for name, _, _ in builtins:
    if f'"{name}"' not in fscript_dict:
        failures.append(f'tests/fuzz/dict/fscript.dict: no line "{name}" (frontend/fscript/builtins.def)')
for op, mnemonic in ops:
    if f'"{mnemonic} "' not in ir_dict:
        failures.append(f'tests/fuzz/dict/ir.dict: no line "{mnemonic} " (ir/opcodes.def, {op})')

# The language reference's list.
m = re.search(r"^## Built-ins\n`([^`]+)`", read("docs/language.md"), re.M)
listed = set(m.group(1).split()) if m else set()
for name, _, _ in builtins:
    if name not in listed:
        failures.append(f"docs/language.md: the list under '## Built-ins' does not name '{name}'")

# A golden case on every backend: some tests/golden/run file calls it.
golden = "".join(read(os.path.join("tests/golden/run", f)) for f in sorted(os.listdir(os.path.join(src, "tests/golden/run"))))
for name, _, _ in builtins:
    if not re.search(r"\b" + name + r"\(", golden):
        failures.append(f"tests/golden/run: no case calls '{name}'")

# Each math row: its interval rule (iv::FN in runtime/math/interval.h) and, for Batch and Trig
# rows, its batch twin of the same arity.
interval_h = read("runtime/math/interval.h")
for op, fn, arity, how in math_rows:
    if not re.search(r"\bInterval " + fn + r"\(", interval_h):
        failures.append(f"runtime/math/interval.h: no interval rule 'Interval {fn}(...)' for ir/opcodes.def's {op}")
    if how in ("Batch", "Trig") and batch_rows.get(fn) != int(arity):
        failures.append(f"runtime/math/batch_functions.def: no FS_BATCH_FN({fn}, {arity}) for ir/opcodes.def's {op}")

# The accuracy each Batch or Trig row promises (docs/language.md) is measured in
# tests/unit/math_test.cpp: it calls math::FN or names it in a UNARY_CASE.
math_test = read("tests/unit/math_test.cpp")
for op, fn, arity, how in math_rows:
    if how in ("Batch", "Trig") and not re.search(r"(\bmath::" + fn + r"\(|UNARY_CASE\(" + fn + r",)", math_test):
        failures.append(f"tests/unit/math_test.cpp: no accuracy test of {fn} (ir/opcodes.def's {op})")

# The recipe names every file that names hypot (std::hypot and Math.hypot in C++ or JavaScript
# are not the built-in; these pages only talk about it).
talk = {"docs/architecture.md", "docs/testing.md", "tests/support/builtins_check.py"}
files = subprocess.run(["git", "-C", src, "grep", "-l", "-w", "hypot"], capture_output=True, text=True).stdout.split()
naming = set()
for rel in files:
    if rel in talk:
        continue
    text = read(rel)
    if re.search(r"(?<!std::)(?<!Math\.)\bhypot\b", text):
        naming.add(rel)
arch = read("docs/architecture.md")
m = re.search(r"\*\*Adding an operation\*\*(.*?)\n\d+\. \*\*", arch, re.S)
recipe = m.group(1) if m else ""
named = set(re.findall(r"`([\w./-]+\.\w+)`", recipe))
for rel in sorted(naming - named):
    failures.append(f"docs/architecture.md: the recipe 'Adding an operation' does not name {rel}, which names hypot")
for rel in sorted(f for f in named if "/" in f and not os.path.exists(os.path.join(src, f))):
    failures.append(f"docs/architecture.md: the recipe names {rel}, which does not exist")

for f in failures:
    print("FAIL", f)
print(f"builtins: {len(builtins)} built-ins, {len(ops)} ops, {len(math_rows)} math rows; "
      f"the recipe names {len(named)} files, hypot is in {len(naming)}; {len(failures)} problem(s)")
sys.exit(1 if failures else 0)
