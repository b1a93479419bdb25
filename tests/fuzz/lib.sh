# What run.sh and campaign.sh share: each target's dictionary and seeds. Sourced; needs $here
# (tests/fuzz), $src (the checkout), $bf (the fuzz build) and $shared (the shared folder).

dict_for() {
  case "$1" in
    fscript_frontend) echo "$here/dict/fscript.dict" ;;
    ir_reader) echo "$here/dict/ir.dict" ;;
    vrml_reader) echo "$here/dict/vrml.dict" ;;
    lsp_server) echo "$here/dict/lsp.dict" ;;
    *) echo "" ;;
  esac
}

# Seeds, copied flat (libFuzzer reads one level): the programs for the front end, the scenes for
# the VRML reader. The generator targets start from their regression corpus alone.
seed() {
  local t="$1" dir="$bf/seeds/$1"
  rm -rf "$dir" && mkdir -p "$dir"
  local n=0
  copy() { while IFS= read -r -d '' f; do n=$((n + 1)); cp "$f" "$dir/seed$n"; done; }
  case "$t" in
    fscript_frontend) find "$src/tests/golden" "$src/examples" "$shared/bench" -name '*.fs' -print0 2>/dev/null | copy ;;
    vrml_reader) find "$src/examples" "$shared/corpus" -name '*.wrl' -size -256k -print0 2>/dev/null | copy ;;
  esac
}
