#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""compare_outputs.py REFERENCE OTHER [MPI_RANKS]: exit 0 when every group,
dataset and attribute of two shockgas-sim files is identical bit for bit,
except the root attributes that describe the run rather than its results.
Used for a one-process run against an MPI run (MPI_RANKS: the rank count the
second file must record) and for an uninterrupted run against a killed and
resumed one.

Bitwise, not within a tolerance: both files come from the same seed streams
through the same arithmetic, so any difference at all is a bug (a realization
run twice or with the wrong seed, a block joined in the wrong order, an
engine state restored incompletely). The comparison, and the one list of
attributes left out, is shockgas.compare's (python/shockgas/compare.py).
"""
import os
import sys

# Run by hand from a clone too (docs/reliability.md): python/ found as the scripts in tools/ find it.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", "tools"))
import shockgas_path  # noqa: E402,F401  (tools/shockgas_path.py)
from shockgas.compare import identical_runs  # noqa: E402


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    ranks = int(sys.argv[3]) if len(sys.argv) == 4 else None
    problems, datasets = identical_runs(sys.argv[1], sys.argv[2], ranks)
    for problem in problems:
        print(f"FAIL: {problem}")
    if problems:
        sys.exit(1)
    print(f"ok: {datasets} datasets and every result attribute identical bit for bit")


if __name__ == "__main__":
    main()
