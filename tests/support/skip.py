"""Skips that cannot hide (the Python tests' side of tests/support/skip.sh): every skip prints one line
and is appended to $FS_SKIP_LOG; a skip because something is missing fails when CI is set."""
import os


def ci():
    return os.environ.get("CI", "") not in ("", "0", "false", "no")


def skip(kind, name, why):
    """kind is "missing" or "machine". True when the caller may skip, False when it must fail."""
    log = os.environ.get("FS_SKIP_LOG")
    if kind == "missing" and ci():
        print(f"FAIL {name}: {why} (CI is set: a check may not be skipped because something is missing)")
        if log:
            with open(log, "a") as f:
                f.write(f"FAILED (not skipped under CI) {name}: {why}\n")
        return False
    print(f"SKIP {name}: {why}")
    if log:
        with open(log, "a") as f:
            f.write(f"skipped {name}: {why}\n")
    return True
