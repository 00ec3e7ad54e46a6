#!/usr/bin/python3
"""Unit test of reproduce-check's HDF5 comparison rules on synthetic results files
(label archive): same toolchain -> bit-identical required; another compiler ->
numbers X with X_sigma must agree within k sqrt(sigma_a^2 + sigma_b^2); date, host
and timings are never compared."""
import importlib.machinery
import importlib.util
import os
import sys
import tempfile

import h5py

here = os.path.dirname(os.path.abspath(__file__))
loader = importlib.machinery.SourceFileLoader("reproduce_check", os.path.join(here, "..", "..", "tools", "reproduce-check"))
spec = importlib.util.spec_from_loader("reproduce_check", loader)
rc = importlib.util.module_from_spec(spec)
loader.exec_module(rc)

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


old = rc.PathNormalizer("/old/build", "/old/src")
new = rc.PathNormalizer("/new/build", "/new/src")


def expect(label, a, b, exact, differences):
    got_exact, got, _ = rc.compare_h5(a, b, old, new, 3.0)
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

if failures:
    print("FAILED:\n  " + "\n  ".join(failures))
    sys.exit(1)
print("all comparison rules hold")
