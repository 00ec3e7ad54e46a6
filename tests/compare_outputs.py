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
import sys

import h5py
import numpy as np

# Root attributes that legitimately differ between two runs of the same
# ensemble: when and how fast it ran, on how much memory.
RUN_DEPENDENT = {"date", "wall_seconds", "cpu_seconds", "peak_memory_bytes"}
# Written only by a run with more than one MPI rank.
DISTRIBUTED_ONLY = {"mpi_ranks"}


def same_value(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def objects(h5file):
    names = [""]
    h5file.visit(names.append)
    return names


def compare(single_path, distributed_path, ranks):
    """single_path: the reference; distributed_path: the file under test."""
    problems = []
    with h5py.File(single_path, "r") as single, h5py.File(distributed_path, "r") as distributed:
        single_names, distributed_names = objects(single), objects(distributed)
        if single_names != distributed_names:
            problems.append(f"objects differ: {sorted(set(single_names) ^ set(distributed_names))}")
        datasets = 0
        for name in single_names:
            if name not in distributed:
                continue
            a, b = single[name] if name else single, distributed[name] if name else distributed
            if isinstance(a, h5py.Dataset):
                datasets += 1
                if not same_value(a[()], b[()]):
                    problems.append(f"dataset /{name} differs")
            skip = RUN_DEPENDENT if not name else set()
            extra = DISTRIBUTED_ONLY if not name else set()
            keys_a = set(a.attrs) - skip
            keys_b = set(b.attrs) - skip - extra
            if keys_a != keys_b:
                problems.append(f"attributes of /{name} differ in names: {sorted(keys_a ^ keys_b)}")
            for key in sorted(keys_a & keys_b):
                if not same_value(a.attrs[key], b.attrs[key]):
                    problems.append(f"attribute {key} of /{name} differs: {a.attrs[key]!r} vs {b.attrs[key]!r}")
        if ranks is not None:
            recorded = distributed.attrs.get("mpi_ranks")
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
