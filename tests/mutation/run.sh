#!/usr/bin/env bash
# Mutation testing: every mutant of tests/mutation/mutants.txt applied, one at a time, to a copy of
# the tree, rebuilt and tested; prints (and with --report writes) which were killed and which
# survived. See docs/testing.md. usage: tests/mutation/run.sh [--only ID,ID] [--work DIR] [--report FILE]
exec python3 "$(dirname "$0")/run.py" "$@"
