#!/usr/bin/env python3
"""Runs a command with a pseudo-terminal as its standard input and output (as a user's shell
would), in the current folder; prints what it wrote and exits with its status. Tests use it for
what a tool does differently on a terminal."""
import os
import pty
import select
import sys

pid, fd = pty.fork()
if pid == 0:
    os.execvp(sys.argv[1], sys.argv[1:])
out = b""
while True:
    try:
        ready, _, _ = select.select([fd], [], [], 60)
        if not ready:
            break
        data = os.read(fd, 65536)
        if not data:
            break
        out += data
    except OSError:  # the child closed the terminal
        break
_, status = os.waitpid(pid, 0)
sys.stdout.write(out.decode(errors="replace").replace("\r\n", "\n"))
sys.exit(os.WEXITSTATUS(status) if os.WIFEXITED(status) else 1)
