#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Unit test of reproduce-check's HDF5 comparison rules (shockgas.compare, shockgas.archive) on
synthetic results files (label archive): same toolchain -> bit-identical required; another compiler
-> numbers X with X_sigma must agree within k sqrt(sigma_a^2 + sigma_b^2); date, host and timings
are never compared, in HDF5 attributes, gnuplot variable dumps and data columns alike; a figure
without a run parameter file is packed with its rule."""
import argparse
import json
import os
import sys
import tarfile
import tempfile

import h5py

from shockgas import archive, compare  # tools/reproduce-check's work (python/ on PYTHONPATH, set by ctest)

work = tempfile.mkdtemp(prefix="archive-compare-")
failures = []


def results_file(name, exponent, sigma, compiler="GNU 12.2.0", date="2026-01-01T00:00:00Z", host="a",
                 chi2=1.7, build="/old/build"):
    path = os.path.join(work, name)
    with h5py.File(path, "w") as f:
        for key, value in {"program": "shockgas-analyze", "version": "v1", "compiler": compiler,
                           "compiler_flags": "-O3 -DNDEBUG", "build_type": "Release", "hdf5_version": "1.10.8",
                           "schema_version": 1,
                           "date": date, "host": host, "input_wall_seconds": 12.5 if host == "a" else 99.0,
                           "input_compiler": compiler,
                           "input_path": build + "/paper_targets/quick/fig1/r0.9.h5"}.items():
            f.attrs[key] = value
        group = f.create_group("decay")
        group.attrs["exponent"] = exponent
        group.attrs["exponent_sigma"] = sigma
        group.attrs["chi2_per_dof"] = chi2
    return path


old = compare.PathNormalizer("/old/build", "/old/src")
new = compare.PathNormalizer("/new/build", "/new/src")


def expect(label, a, b, exact, differences):
    got_exact, got, _ = compare.compare_h5(a, b, old, new, 3.0)
    if got_exact != exact or len(got) != differences:
        failures.append(f"{label}: exact={got_exact} differences={got}")
    print(f"{label}: exact={got_exact}, {len(got)} difference(s) {got}")


reference = results_file("a.h5", 0.694, 0.010)
# Same code and compiler, another day, host and path: identical.
expect("same toolchain, other date/host/path", reference,
       results_file("b.h5", 0.694, 0.010, date="2030-05-05T00:00:00Z", host="b",
                    build="/new/build"), True, 0)
# Same toolchain, last bit of the exponent changed: different.
expect("same toolchain, exponent changed by 1 ulp", reference, results_file("c.h5", 0.6940000000000001, 0.010, build="/new/build"),
       True, 1)
# Another compiler: 0.694 vs 0.71 with sigma 0.010 each -> |d| = 0.016 < 3*0.0141: agree (chi2 not compared).
expect("clang, within sigma", reference, results_file("d.h5", 0.71, 0.010, compiler="Clang 14.0.6", chi2=1.9), False, 0)
# Another compiler: 0.694 vs 0.75 -> |d| = 0.056 > 0.042: different.
expect("clang, outside sigma", reference, results_file("e.h5", 0.75, 0.010, compiler="Clang 14.0.6"), False, 1)



def merged_run(name, versions, threshold=0.01):
    path = os.path.join(work, name)
    with h5py.File(path, "w") as f:
        f.attrs["schema_version"] = 1
        f.attrs["velocity_threshold"] = threshold
        f.attrs["merged_from"] = "\n".join(f"/b/r.part{k}.h5 (realizations {10 * k} to {10 * k + 9}, shockgas {v})"
                                           for k, v in enumerate(versions))
    return path


# A merged run's parts made at other commits of the same simulator: the same data (merged_from's
# versions are provenance); another threshold is still a difference.
merged = merged_run("m0.h5", ["ee02623", "ee02623"])
expect("merged parts of other versions", merged, merged_run("m1.h5", ["77d27cb", "ee02623-dirty"]), True, 0)
expect("merged parts, other threshold", merged, merged_run("m2.h5", ["ee02623", "ee02623"], 0.001), True, 1)


def text_file(name, text):
    path = os.path.join(work, name)
    with open(path, "w") as handle:
        handle.write(text)
    return path


def expect_bytes(label, a, b, same):
    why = compare.compare_bytes(a, b, "data", old, new)
    if (why is None) != same:
        failures.append(f"{label}: {why}")
    print(f"{label}: {'identical' if why is None else why}")


# gnuplot-vars dumps of a run's root attributes (fig5, fig_tradeoff): date, host, timings and the
# code version are not compared; a physical value is.
gp = "ref_cpu_seconds = {cpu}\nref_date = \"{date}\"\nref_version = \"{v}\"\nref_restitution = {r}\n"
expect_bytes("gp: other date, CPU and version", text_file("a.gp", gp.format(cpu=2.8, date="2026-01-01", v="a", r=0.9)),
             text_file("b.gp", gp.format(cpu=3.1, date="2026-02-02", v="b", r=0.9)), True)
expect_bytes("gp: other restitution", text_file("c.gp", gp.format(cpu=2.8, date="2026-01-01", v="a", r=0.9)),
             text_file("d.gp", gp.format(cpu=2.8, date="2026-01-01", v="a", r=0.8)), False)
# fig_tradeoff's table: the cpu_seconds column is what the run cost, not compared; the others are.
table = ("# cost and deviation\n# shockgas-analyze v1, from {build}/x.h5\n"
         "# delta sticky cpu_seconds max_abs_deviation\n0.001 0 {cpu} {dev}\n0.01 1 0.72 0.021\n")
# The analysis version in the header is provenance (a file made at an earlier commit is the same data).
expect_bytes("dat: other analysis version", text_file("v.dat", table.format(build="/old/build", cpu=93.5, dev=0.0083)),
             text_file("w.dat", table.format(build="/new/build", cpu=93.5, dev=0.0083).replace(" v1,", " v2-dirty,")),
             True)
expect_bytes("dat: other CPU seconds", text_file("a.dat", table.format(build="/old/build", cpu=93.5, dev=0.0083)),
             text_file("b.dat", table.format(build="/new/build", cpu=101.2, dev=0.0083)), True)
expect_bytes("dat: other deviation", text_file("c.dat", table.format(build="/old/build", cpu=93.5, dev=0.0083)),
             text_file("d.dat", table.format(build="/new/build", cpu=93.5, dev=0.0084)), False)

# pack: a figure without a parameter file of runs (fig_tail: the sampler's options are in its rule)
# is packed with paper_targets/<figure>.cmake as its parameters, so that the whole-pipeline `archive`
# target does not stop there.
source = os.path.join(work, "source")
build = os.path.join(work, "build")
os.makedirs(os.path.join(source, "paper_targets"))
text_file(os.path.join("source", "paper_targets", "fig_tail.cmake"), "# the sampler's options\n")
os.makedirs(os.path.join(build, "paper_targets", "quick", "fig_tail"))
os.makedirs(os.path.join(build, "figures", "quick"))
with h5py.File(os.path.join(build, "paper_targets", "quick", "fig_tail", "tail.h5"), "w") as f:
    f.attrs["program"] = "shockgas-tail"
    f.attrs["schema_version"] = 1
for extension in ("png", "pdf"):
    text_file(os.path.join("build", "figures", "quick", f"fig_tail.{extension}"), "figure\n")
packed = archive.pack(argparse.Namespace(output_dir=work, build_dir=build, source_dir=source, figures="fig_tail",
                                    fidelity="quick", max_raw_mb=50.0, suffix="", toolchain=[]))
archives = [n for n in os.listdir(work) if n.endswith(".tar.gz")]
if packed != 0 or len(archives) != 1:
    failures.append(f"pack of fig_tail: status {packed}, archives {archives}")
else:
    with tarfile.open(os.path.join(work, archives[0])) as tar:
        manifest = json.load(tar.extractfile(next(m for m in tar.getmembers() if m.name.endswith("/MANIFEST"))))
    parameters = [e["path"] for e in manifest["files"] if e["category"] == "parameters"]
    if parameters != ["params/fig_tail.cmake"]:
        failures.append(f"pack of fig_tail: parameters {parameters}")
    print(f"pack of fig_tail: parameters {parameters}")

if failures:
    print("FAILED:\n  " + "\n  ".join(failures))
    sys.exit(1)
print("all comparison rules hold")
