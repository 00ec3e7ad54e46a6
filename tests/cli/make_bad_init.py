# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes malformed --init files for the CLI tests (needs h5py)."""
import sys

import h5py
import numpy as np

directory = sys.argv[1]


def write(name, ring_length=8.0, **datasets):
    with h5py.File(f"{directory}/{name}.h5", "w") as f:
        if ring_length is not None:
            f.attrs["ring_length"] = ring_length
        for key, value in datasets.items():
            f[key] = np.asarray(value, dtype=float)


x = np.arange(8.0)
v = np.linspace(-1, 1, 8)
write("missing_velocity", position=x)
write("length_mismatch", position=x, velocity=v[:5])
write("unsorted", position=x[::-1], velocity=v)
write("out_of_range", position=x + 1.0, velocity=v)
write("nan_velocity", position=x, velocity=np.where(v > 0.9, np.nan, v))
write("no_ring_length", ring_length=None, position=x, velocity=v)
write("good", position=x, velocity=v)
# Not equally spaced (particle 1 off the lattice): a start shockgas-sim runs, but shockgas-burgers,
# whose profile is built on the lattice of the start, refuses, naming the file and the particle.
write("off_lattice", position=np.array([0.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]), velocity=v)
# Speeds so large that positions would overflow by the default t_max = 1000 (|v| t up to 1e308): refused up front.
write("too_fast", position=x, velocity=v * 1e305)
