# The prologue of every tests/cli/<feature>.sh (sourced; the feature file's arguments are
# FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF): the tools, the check helpers, the fixtures.
F="$1"
SRC="$2"
R="${3:-}"
D="${4:-}"
. "$SRC/tests/cli/lib.sh"
. "$SRC/tests/cli/fixtures.sh"
