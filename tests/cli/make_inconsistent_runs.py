# SPDX-License-Identifier: GPL-3.0-or-later
"""Copies a shockgas-sim output (with snapshots) into files whose datasets or
attributes disagree, as damage or a hand edit would leave them (needs h5py).

    make_inconsistent_runs.py SOURCE.h5 DIR

The readers must refuse each with one line naming the file and what is wrong,
never read beyond a dataset's end."""
import shutil
import sys

import h5py

source, directory = sys.argv[1], sys.argv[2]


def damaged(name, change):
    path = f"{directory}/{name}.h5"
    shutil.copyfile(source, path)
    with h5py.File(path, "r+") as f:
        change(f)


def shorten(dataset):
    def change(f):
        data = f[dataset][...]
        del f[dataset]
        f[dataset] = data.reshape(-1)[: data.size // 2]
    return change


def set_attribute(name, value):
    def change(f):
        f.attrs[name] = value
    return change


# The snapshot's velocity shorter than its positions (unchecked, shockgas-dump would print heap garbage).
damaged("short_velocity", shorten("snapshots/0/velocity"))
# The collisions shorter than realizations x times (unchecked, readers would give 1e-314).
damaged("short_collisions", shorten("timeseries/collisions_per_particle"))
# A malformed list of sample times (unchecked, shockgas-merge would say only "stod").
damaged("bad_sample_times", set_attribute("sample_times", "2,abc"))
# A status no output has (a checkpoint's, without its /checkpoint group).
damaged("unknown_status", set_attribute("status", "checkpoint"))
