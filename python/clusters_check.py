#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Recount the clusters of a shockgas-analyze `clusters` results file with scipy, independently of
the C++ union-find, and check agreement.

    /usr/bin/python3 python/clusters_check.py CLUSTERS_RESULTS.h5 [--run RUN.h5] [--tolerance 1e-9]

Reads each /clusters<k> section and the shockgas-spheres output it was computed from (the root
attribute `input_path` or `input<k>_path`, found and checked against the recorded provenance as
refit_check.py does; or --run for a single input). Estimator (analysis/src/clusters.cpp), redone here:
  * each realization's density row (field_cells^d values, x fastest) reshaped to a d-dimensional
    array (axes z, y, x in numpy's order; the order does not change connectivity), rows with NaN
    (a realization that did not reach the snapshot) left out;
  * cells at density >= threshold labelled by scipy.ndimage.label with face connectivity
    (generate_binary_structure(d, 1)), then the labels meeting across each pair of opposite box
    faces merged (the box is periodic);
  * a cluster's mass = sum of density x mean_count over its cells (mean_count = N / cells);
  * per snapshot: clusters per realization, the largest mass and sum m / N averaged over
    realizations, sum m^2 / sum m pooled; sigmas by the delete-one jackknife over realizations,
    sqrt((n-1)/n sum (theta_i - mean theta)^2), n/a for one realization; the pooled masses,
    rounded to whole particles, counted in the results file's bin_edges.
Exit status 0 when every number agrees within the relative tolerance (bin counts exactly), 1
otherwise, 2 with one line "clusters_check.py: error: ..." for bad input, 77 (SKIP) when numpy, scipy
or h5py is missing.
"""
import importlib.util
import sys

SKIP = 77
# A machine without the packages: ctest's python.clusters_check skips (SKIP_RETURN_CODE 77), naming them.
MISSING = [name for name in ("numpy", "scipy", "h5py") if importlib.util.find_spec(name) is None]
if MISSING:  # pragma: no cover - depends on the machine
    print("SKIP: clusters_check.py needs numpy, scipy and h5py: %s missing; run it with Debian's /usr/bin/python3 "
          "(python3-numpy, python3-scipy, python3-h5py)" % ", ".join(MISSING))
    sys.exit(SKIP)
import numpy as np  # noqa: E402
from scipy import ndimage  # noqa: E402
# refit_check's way of finding the analysed run from the recorded provenance, and the shockgas module
# (both beside this script; refit_check refuses a missing module in one line, exit 2, before we import it).
from refit_check import SPHERES_RUN_HELP, InputError, agree, analysed_runs, check_arguments  # noqa: E402
import shockgas  # noqa: E402
from shockgas.cli import fail  # noqa: E402


def periodic_clusters(dense, density, mean_count):
    """Masses and cell counts of the face-connected clusters of `dense` on a periodic box."""
    labels, count = ndimage.label(dense, structure=ndimage.generate_binary_structure(dense.ndim, 1))
    parent = list(range(count + 1))

    def root(a):
        while parent[a] != a:
            a = parent[a]
        return a
    for axis in range(dense.ndim):  # the first and last slice along each axis are neighbours
        first, last = np.take(labels, 0, axis=axis), np.take(labels, -1, axis=axis)
        for a, b in zip(first[(first > 0) & (last > 0)], last[(first > 0) & (last > 0)]):
            parent[root(int(a))] = root(int(b))
    merged = np.array([root(a) for a in range(count + 1)])[labels]
    mass = np.bincount(merged.ravel(), weights=(density * mean_count).ravel(), minlength=count + 1)[1:]
    cells = np.bincount(merged.ravel(), minlength=count + 1)[1:]
    return mass[cells > 0], cells[cells > 0]


def jackknife(numerator, denominator):
    """sum numerator / sum denominator (0 where the denominator is 0) and its delete-one jackknife
    sigma over realizations (NaN for one)."""
    def ratio(keep):
        bottom = denominator[keep].sum()
        return numerator[keep].sum() / bottom if bottom > 0 else 0.0
    n = len(numerator)
    value = ratio(np.ones(n, bool))
    if n < 2:
        return value, float("nan")
    replicas = np.array([ratio(np.arange(n) != i) for i in range(n)])
    return value, float(np.sqrt((n - 1) / n * np.sum((replicas - replicas.mean()) ** 2)))


def recount(run, threshold, edges_of):
    """Per snapshot time, the numbers clusters.cpp computes, from the run alone."""
    a = run.attrs
    d, side, particles = int(a["dimension"]), int(a["field_cells"]), float(a["particles"])
    mean_count = particles / side ** d
    out = {}
    for snapshot in run.snapshots:
        rows = snapshot.data["density"]
        kept = [row for row in rows if not np.isnan(row).any()]
        if not kept:
            continue
        per = {"count": [], "largest": [], "mass": [], "mass2": []}
        pooled = []
        for row in kept:
            field = row.reshape((side,) * d)
            mass, _ = periodic_clusters(field >= threshold, field, mean_count)
            per["count"].append(len(mass))
            per["largest"].append(mass.max() if len(mass) else 0.0)
            per["mass"].append(mass.sum())
            per["mass2"].append((mass ** 2).sum())
            pooled.extend(np.round(mass))
        per = {k: np.array(v, float) for k, v in per.items()}
        ones = np.ones(len(kept))
        time = float(snapshot.attrs["time"])
        edges = edges_of(time)
        bins = np.clip(np.searchsorted(edges, pooled, side="right") - 1, 0, len(edges) - 2)
        out[time] = {"realizations": len(kept), "clusters": jackknife(per["count"], ones),
                     "largest_mass": jackknife(per["largest"], ones),
                     "mean_mass": jackknife(per["mass2"], per["mass"]),
                     "clustered_fraction": jackknife(per["mass"], particles * ones),
                     "bin_clusters": np.bincount(bins, minlength=len(edges) - 1).astype(float)}
    return out


def main(argv=None):
    args = check_arguments(__doc__.split("\n")[0], SPHERES_RUN_HELP, 1e-9,
                           "relative agreement required (the two add a cluster's cells in other orders)", argv)
    ok, compared = True, 0
    for section, run_path, run in analysed_runs(args.results, "clusters", "clusters", args.run):
        snapshots = list(section.groups["snapshots"].groups.values())
        by_time = {float(s.attrs["time"]): s for s in snapshots}
        ours = recount(run, float(section.attrs["threshold"]), lambda t: by_time[t].data["bin_edges"])
        if sorted(ours) != sorted(by_time):
            print(f"{run_path}: snapshot times C++ {sorted(by_time)} scipy {sorted(ours)} FAIL")
            ok = False
            continue
        for time, cpp in sorted(by_time.items()):
            py = ours[time]
            line = [f"{run_path} t = {time:g}:"]
            good = cpp.attrs["realizations"] == py["realizations"]
            for name in ("clusters", "largest_mass", "mean_mass", "clustered_fraction"):
                value, sigma = py[name]
                same = agree(cpp.attrs[name], value, args.tolerance) and \
                    agree(cpp.attrs[name + "_sigma"], sigma, args.tolerance)
                line.append(f"{name} {cpp.attrs[name]:.10g} vs {value:.10g}{'' if same else ' FAIL'}")
                good &= same
            same_bins = np.array_equal(cpp.data["bin_clusters"], py["bin_clusters"])
            line.append("bins equal" if same_bins else "bins FAIL")
            print("  ".join(line) + ("  ok" if good and same_bins else ""))
            ok &= bool(good and same_bins)
            compared += 1
    print(f"{compared} snapshots compared, {'all agree' if ok else 'DISAGREEMENT'}")
    return 0 if ok and compared > 0 else 1


if __name__ == "__main__":
    try:
        sys.exit(main())
    except (InputError, OSError, shockgas.SchemaError) as error:
        fail(error)
