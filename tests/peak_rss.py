#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Runs a command and appends its peak resident set to a file: `peak_rss.py FILE COMMAND...` writes the line
"RANK KB" (RANK from Open MPI's environment, - without it; KB from getrusage of the finished child: its maximum
resident set size).  Under `mpirun -n P peak_rss.py FILE btob ...` each rank's line lands in FILE.  Exits with the
command's status."""
import os
import resource
import subprocess
import sys


def main(out, cmd):
    rc = subprocess.run(cmd).returncode
    kb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    with open(out, "a") as f:  # one short line per rank: an append of a few bytes is atomic
        f.write(f"{os.environ.get('OMPI_COMM_WORLD_RANK', '-')} {kb}\n")
    return rc


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2:]))
