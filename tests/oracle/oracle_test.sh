#!/bin/bash
# The node oracle over its fixed seeds (tests/oracle/js_oracle.cpp): 2,000 generated programs and
# every transcendental built-in, on every backend and under node. ./dev.sh oracle runs fresh seeds.
. "$(dirname "$0")/../support/skip.sh"
oracle="$1" prelude="$2"
if ! command -v node > /dev/null; then
  fs_skip missing oracle_node 'node not found (apt-get install nodejs)' && exit 77
  exit 1
fi
exec "$oracle" --prelude "$prelude" --seed 1 --programs 2000
