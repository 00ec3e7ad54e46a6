#!/usr/bin/python3
"""same_datasets.py A.h5 B.h5: exit 0 when two shockgas output files hold the
same run, bit for bit; print the first differences and exit 1 otherwise.

Compared exactly (array_equal with NaN == NaN, no tolerance: the same seeds
and the same arithmetic must give the same doubles): every dataset, every
group, every attribute of every object. Ignored: the root attributes that
record when, where and how fast a run was made, and how it was run (which
differ between an uninterrupted run, a resumed one and an MPI one of the same
ensemble), listed in IGNORED_ROOT_ATTRIBUTES.
"""
import sys

import h5py
import numpy as np

IGNORED_ROOT_ATTRIBUTES = {"date", "host", "wall_seconds", "cpu_seconds", "peak_memory_bytes", "mpi_ranks"}


def items(path):
    """Every object and attribute of the file as {name: value}."""
    out = {}
    with h5py.File(path, "r") as f:
        def attributes(name, obj):
            for key, value in obj.attrs.items():
                if name == "/" and key in IGNORED_ROOT_ATTRIBUTES:
                    continue
                out[f"{name}@{key}"] = np.asarray(value)

        attributes("/", f)

        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                out[name] = obj[()]
            else:
                out[name] = "group"
            attributes(name, obj)

        f.visititems(visit)
    return out


def same(a, b):
    if isinstance(a, str) or isinstance(b, str):
        return a == b
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or a.dtype != b.dtype:
        return False
    if a.dtype.kind == "f":
        return np.array_equal(a, b, equal_nan=True)
    return np.array_equal(a, b)


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip().splitlines()[0], file=sys.stderr)
        return 2
    first, second = items(argv[1]), items(argv[2])
    differences = []
    for name in sorted(set(first) | set(second)):
        if name not in first or name not in second:
            differences.append(f"{name}: only in {argv[1] if name in first else argv[2]}")
        elif not same(first[name], second[name]):
            differences.append(f"{name}: differs")
    for line in differences[:20]:
        print(line)
    if differences:
        print(f"FAIL: {len(differences)} differences between {argv[1]} and {argv[2]}")
        return 1
    print(f"ok: {len(first)} objects and attributes identical")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
