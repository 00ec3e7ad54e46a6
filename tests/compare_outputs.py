#!/usr/bin/env python3
"""compare_outputs.py REFERENCE OTHER [MPI_RANKS]: exit 0 when every group,
dataset and attribute of two shockgas-sim files is identical bit for bit,
except the root attributes that describe the run rather than its results.
Used for a one-process run against an MPI run (MPI_RANKS: the rank count the
second file must record) and for an uninterrupted run against a killed and
resumed one.

Bitwise, not within a tolerance: both files come from the same seed streams
through the same arithmetic, so any difference at all is a bug (a realization
run twice or with the wrong seed, a block joined in the wrong order, an
engine state restored incompletely).
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", "python"))
import shockgas  # noqa: E402  (python/shockgas of this source tree)

# Root attributes that legitimately differ between two runs of the same
# ensemble: when and how fast it ran, on how much memory.
RUN_DEPENDENT = {"date", "wall_seconds", "cpu_seconds", "peak_memory_bytes"}
# Written only by a run with more than one MPI rank.
DISTRIBUTED_ONLY = {"mpi_ranks"}


def same_value(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def objects(path):
    """{object path: (attributes as stored, dataset value or None)}, in the file's order."""
    return {name: (attrs, value) for name, attrs, value in shockgas.walk(path, raw=True)}


def compare(single_path, distributed_path, ranks):
    """single_path: the reference; distributed_path: the file under test."""
    problems = []
    single, distributed = objects(single_path), objects(distributed_path)
    if list(single) != list(distributed):
        problems.append(f"objects differ: {sorted(set(single) ^ set(distributed))}")
    datasets = 0
    for name, (attrs_a, value_a) in single.items():
        if name not in distributed:
            continue
        attrs_b, value_b = distributed[name]
        if value_a is not None:
            datasets += 1
            if not same_value(value_a, value_b):
                problems.append(f"dataset {name} differs")
        skip = RUN_DEPENDENT if name == "/" else set()
        extra = DISTRIBUTED_ONLY if name == "/" else set()
        keys_a = set(attrs_a) - skip
        keys_b = set(attrs_b) - skip - extra
        if keys_a != keys_b:
            problems.append(f"attributes of {name} differ in names: {sorted(keys_a ^ keys_b)}")
        for key in sorted(keys_a & keys_b):
            if not same_value(attrs_a[key], attrs_b[key]):
                problems.append(f"attribute {key} of {name} differs: {attrs_a[key]!r} vs {attrs_b[key]!r}")
    if ranks is not None:
        recorded = distributed["/"][0].get("mpi_ranks")
        if recorded != ranks:
            problems.append(f"mpi_ranks is {recorded!r}, expected {ranks}")
    if datasets == 0:
        problems.append("no datasets compared")
    return problems, datasets


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    ranks = int(sys.argv[3]) if len(sys.argv) == 4 else None
    problems, datasets = compare(sys.argv[1], sys.argv[2], ranks)
    for problem in problems:
        print(f"FAIL: {problem}")
    if problems:
        sys.exit(1)
    print(f"ok: {datasets} datasets and every result attribute identical bit for bit")


if __name__ == "__main__":
    main()
