"""The skip rules of tests/support/skip.sh for Python tests: a visible skip, logged to FS_SKIP_LOG,
and a failure (appended to `failures`) when CI is set."""
import os


def skip(name, why, failures):
    ci = os.environ.get("CI", "") not in ("", "0", "false", "no")
    print(f"SKIP {name}: {why}")
    if os.environ.get("FS_SKIP_LOG"):
        with open(os.environ["FS_SKIP_LOG"], "a") as log:
            log.write(f"{'FAILED (not skipped under CI)' if ci else 'skipped'} {name}: {why}\n")
    if ci:
        failures.append(f"{name}: {why} (CI is set: a check may not be skipped because something is missing)")
