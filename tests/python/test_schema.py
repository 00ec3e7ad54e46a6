#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Schema drift check: a shockgas-sim output against the "Output files" section of
docs/cli-and-output.md, and the Python module shockgas against both.

    PYTHONPATH=python /usr/bin/python3 tests/python/test_schema.py RUN.h5 [--doc docs/cli-and-output.md]

The names come from the documentation itself (every `backticked` name in the "Root attributes" list
and every row of the datasets table), so the test fails when the C++ writer, the documentation, or
the Python reader drift apart. In the file (raw HDF5, through shockgas.open_file): shapes against
the table (R realizations, K sample times, `clusters` per snapshot, bins + 1 / R x (bins + 2) for
histograms), dtypes against the kinds below. Through shockgas.read_run: every documented dataset is
there, and every documented attribute comes back as str, int or float as its kind says.
Exit status 0 ok, 1 drift, 2 with one line "test_schema.py: error: ..." for a bad option, 77 (SKIP)
without h5py/numpy.
"""
import os
import re
import sys

SKIP = 77
try:
    import h5py  # noqa: F401  (shockgas's; imported here so that its absence is a skip)
    import numpy as np
except ImportError as error:  # pragma: no cover
    print("SKIP: test_schema.py needs h5py and numpy (%s); run with Debian's /usr/bin/python3" % error)
    sys.exit(SKIP)
# python/shockgas from PYTHONPATH (ctest's): missing, the test fails rather than skips.
import shockgas  # noqa: E402
from shockgas.cli import ArgumentParser  # noqa: E402  (a bad option in one line, exit status 2)

# Attribute kinds the readers rely on (analysis/, python/): strings are parsed as text, the rest as numbers.
STRING_ATTRIBUTES = {"subthreshold", "sample_times", "snapshot_times", "histogram_times", "init_file",
                     "init_file_sha256", "simulator_sha256", "positions", "velocity_distribution", "initial_condition", "engine", "status", "program", "version", "compiler",
                     "compiler_flags", "build_type", "hdf5_version", "host", "date", "merged_by", "merged_date",
                     "merged_from"}
INTEGER_ATTRIBUTES = {"particles", "samples_per_decade", "histogram_bins", "realizations", "seed",
                      "stall_events_min", "schema_version", "total_collisions", "first_realization", "mpi_ranks"}
# Documented root attributes that only some runs carry: mpi_ranks, written by an MPI run alone; the
# merged_* record of shockgas-merge, by a merged file alone.
OPTIONAL_ATTRIBUTES = {"mpi_ranks", "merged_by", "merged_date", "merged_from"}
INTEGER_DATASETS = {"realization_status", "first_particle", "realization", "collisions"}


def documented_schema(path):
    text = open(path, encoding="utf-8").read()
    section = text.split("## Output files", 1)[1].split("\n## ", 1)[0]
    root_part, table_part = section.split("\nDatasets (", 1)
    attributes = set(re.findall(r"`([a-z_0-9]+)`", root_part.split("Root attributes", 1)[1]))
    attributes -= {"complete", "interrupted", "collapsed"}      # values of `status`, not names
    rows = re.findall(r"^\| `([^`]+)` \| ([^|]+) \|", table_part, flags=re.M)
    return attributes, [(p, s.strip()) for p, s in rows]


def expand(path):
    """'/snapshots/<i>/{position,velocity}' -> ('/snapshots/<i>/', ['position', 'velocity'])."""
    m = re.match(r"(.*/)\{([^}]*)\}$", path)
    return (m.group(1), m.group(2).split(",")) if m else (path.rsplit("/", 1)[0] + "/", [path.rsplit("/", 1)[1]])


def main(argv=None):
    ap = ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run")
    ap.add_argument("--doc", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs",
                                                  "cli-and-output.md"))
    args = ap.parse_args(argv)
    attributes, rows = documented_schema(args.doc)
    problems = []
    run = shockgas.read_run(args.run)
    for name in sorted(attributes & set(run.attrs)):
        want = str if name in STRING_ATTRIBUTES else (int if name in INTEGER_ATTRIBUTES else float)
        if type(run.attrs[name]) is not want:
            problems.append("shockgas.read_run gives attribute %s as %s, expected %s"
                            % (name, type(run.attrs[name]).__name__, want.__name__))
    with shockgas.open_file(args.run) as f:
        for name in sorted(attributes):
            if name not in f.attrs:
                if name not in OPTIONAL_ATTRIBUTES:
                    problems.append("root attribute %s documented but missing" % name)
                continue
            value = f.attrs[name]
            kind = np.asarray(value).dtype.kind
            want = "S" if name in STRING_ATTRIBUTES else ("i" if name in INTEGER_ATTRIBUTES else "f")
            if kind not in ({"S", "O", "U"} if want == "S" else {want}):
                problems.append("root attribute %s has dtype kind %s, expected %s" % (name, kind, want))
        R = int(f.attrs["realizations"])
        K = len(f["timeseries/time"]) if "timeseries/time" in f else -1
        bins = int(f.attrs["histogram_bins"])
        checked = 0
        for path, shape in rows:
            base, names = expand(path)
            if base.startswith("/collapse") and "collapse" not in f:
                continue                                  # "present when a delta = 0 run collapsed"
            parents = [base]
            if "<" in base:                               # every group instance: <i>, <h>, <c>
                head, _, tail = base.partition("<")
                tail = tail.split(">", 1)[1]
                group = head.rstrip("/")
                if group not in f:
                    problems.append("group %s documented but missing" % group)
                    continue
                parents = [head + child + tail for child in f[group].keys()]
            for parent in parents:
                for name in names:
                    if name in ("…", "..."):
                        continue
                    full = parent + name
                    if full not in f:
                        problems.append("dataset %s documented but missing" % full)
                        continue
                    if full not in run:
                        problems.append("dataset %s is in the file but not in shockgas.read_run's Run" % full)
                    ds = f[full]
                    checked += 1
                    want = "i" if name in INTEGER_DATASETS else "f"
                    if ds.dtype.kind != want:
                        problems.append("%s has dtype %s, expected kind %s" % (full, ds.dtype, want))
                    expected = {"K": (K,), "R×K": (R, K), "R": (R,), "bins+1": (bins + 1,),
                                "R×(bins+2)": (R, bins + 2)}.get(shape.replace(" ", ""))
                    if expected is not None and ds.shape != expected:
                        problems.append("%s has shape %s, the documentation says %s = %s" % (full, ds.shape, shape, expected))
                    if shape == "clusters":
                        sizes = {f[parent + n].shape for n in names if parent + n in f}
                        if len(sizes) != 1 or len(ds.shape) != 1:
                            problems.append("%s: fields of one snapshot differ in length %s" % (parent, sizes))
                    if shape.startswith("R×K") and K < 1:
                        problems.append("no sample times")
    for p in problems:
        print("DRIFT:", p)
    print("%d documented attributes, %d datasets checked, %d problems" % (len(attributes), checked, len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
