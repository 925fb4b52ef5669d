#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Runs a command and appends its peak resident set to a file: `peak_rss.py FILE COMMAND...` writes the line
"RANK KB" (RANK from Open MPI's environment, - without it; KB from getrusage of the finished child: its maximum
resident set size).  Under `mpirun -n P peak_rss.py FILE btob ...` each rank's line lands in FILE.  Exits with the
command's status.

`peak_rss.py --peaks FILE` prints "LARGEST MEDIAN" of such a file's peaks in KB (the median of an even count: the
lower one), for the memory checks of tests/mpi_sweeps.sh and analyses/mpi_scaling.sh."""
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


def peaks(path):
    with open(path) as f:
        kb = sorted(int(line.split()[1]) for line in f if line.strip())
    print(kb[-1], kb[(len(kb) - 1) // 2])
    return 0


if __name__ == "__main__":
    if sys.argv[1] == "--peaks":
        sys.exit(peaks(sys.argv[2]))
    sys.exit(main(sys.argv[1], sys.argv[2:]))
