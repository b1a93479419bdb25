"""Reading a program's pseudo-terminal, for the tests that drive a tool as a person would."""
import os
import re
import select
import time


def read_until(fd, pattern, timeout=20.0):
    """Reads the terminal until `pattern` (a regex) appears in what came since the last call."""
    text = ""
    end = time.time() + timeout
    while time.time() < end:
        ready, _, _ = select.select([fd], [], [], 0.1)
        if not ready:
            continue
        try:
            chunk = os.read(fd, 65536).decode("utf-8", "replace")
        except OSError:
            break
        if not chunk:
            break
        text += chunk
        if re.search(pattern, text):
            return text
    return text
