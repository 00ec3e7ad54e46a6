#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Refit the velocity-tail exponents of a shockgas-analyze `late-decay` results file with scipy,
independently of the C++ (GSL) code, and check agreement.

    /usr/bin/python3 python/tails_check.py LATE_DECAY_RESULTS.h5 [--run RUN.h5] [--tolerance 1e-4]

Reads each /late_decay<k> section's tail_times, tail_gamma and tail_gamma_sigma, and the
shockgas-spheres output it was computed from (the root attribute `input<k>_path`, found and checked
against the recorded provenance as refit_check.py does; or --run for a single input). Estimator
(analysis/src/velocity_distribution.cpp, fit_pooled_tail), redone here:
  * the histogram of u = (v_k - V_k) / sqrt(T) over realizations and components: counts n_b on
    histogram_bins equal bins of [-histogram_range, histogram_range];
  * rms of u over the bins (bin centres, counts as weights); each bin b of the left half folded with
    its mirror, n = n_b + n_(bins-1-b), at |u| = |centre| / rms;
  * tail points: |u| >= 1.5 and 1/sqrt(n) <= 0.3 (the Poisson error of ln n), at least 4 of them;
  * at fixed gamma, ln(n / width) = a - c |u|^gamma by weighted least squares (sigma 1/sqrt(n));
    gamma minimises that chi2 on [0.5, 8] (scipy.optimize.minimize_scalar, bounded);
  * sigma: the Delta chi2 = 1 half-width sqrt(2 / chi2''(gamma)), the curvature by central
    differences.
Exit status 0 when every gamma agrees within the absolute tolerance and every sigma within 1 % (the
two searches stop at different points of a flat minimum), 1 otherwise, 2 with one line
"tails_check.py: error: ..." for bad input, 77 (SKIP) when numpy, scipy or h5py is missing.
"""
import importlib.util
import sys

SKIP = 77
# A machine without the packages: ctest's python.tails_check skips (SKIP_RETURN_CODE 77), naming them.
MISSING = [name for name in ("numpy", "scipy", "h5py") if importlib.util.find_spec(name) is None]
if MISSING:  # pragma: no cover - depends on the machine
    print("SKIP: tails_check.py needs numpy, scipy and h5py: %s missing; run it with Debian's /usr/bin/python3 "
          "(python3-numpy, python3-scipy, python3-h5py)" % ", ".join(MISSING))
    sys.exit(SKIP)
import numpy as np  # noqa: E402
from scipy import optimize  # noqa: E402
# refit_check's way of finding the analysed run from the recorded provenance, and the shockgas module.
from refit_check import SPHERES_RUN_HELP, InputError, agree, analysed_runs, check_arguments  # noqa: E402
import shockgas  # noqa: E402
from shockgas.cli import fail  # noqa: E402

TAIL_START = 1.5           # in units of the rms of u
MAX_RELATIVE_ERROR = 0.3   # of the folded count
SIGMA_TOLERANCE = 0.01     # relative, for the Delta chi2 = 1 width


def chi2_at(u, log_density, sigma, gamma):
    """chi2 of the weighted straight line ln P = a - c u^gamma."""
    x = u ** gamma
    w = 1.0 / sigma ** 2
    design = np.vstack([np.ones_like(x), x]).T
    coefficients, *_ = np.linalg.lstsq(design * np.sqrt(w)[:, None], log_density * np.sqrt(w), rcond=None)
    residual = log_density - design @ coefficients
    return float(np.sum(w * residual ** 2))


def refit(counts, range_):
    """(gamma, sigma) of one pooled histogram, or (nan, nan) where the C++ finds too few tail bins."""
    bins = len(counts)
    edges = np.linspace(-range_, range_, bins + 1)
    centres = 0.5 * (edges[:-1] + edges[1:])
    rms = np.sqrt(np.sum(counts * centres ** 2) / np.sum(counts))
    half = np.arange(bins // 2)
    folded = counts[half] + counts[bins - 1 - half]
    u = np.abs(centres[half]) / rms
    keep = (u >= TAIL_START) & (folded > 0)
    keep[keep] &= 1.0 / np.sqrt(folded[keep]) <= MAX_RELATIVE_ERROR
    if keep.sum() < 4:
        return float("nan"), float("nan")
    u, n = u[keep], folded[keep]
    log_density = np.log(n / np.diff(edges)[half][keep])
    sigma = 1.0 / np.sqrt(n)
    best = optimize.minimize_scalar(lambda g: chi2_at(u, log_density, sigma, g), bounds=(0.5, 8.0),
                                    method="bounded", options={"xatol": 1e-8})
    gamma = float(best.x)
    h = 1e-3 * gamma
    curvature = (chi2_at(u, log_density, sigma, gamma + h) - 2.0 * chi2_at(u, log_density, sigma, gamma)
                 + chi2_at(u, log_density, sigma, gamma - h)) / h ** 2
    return gamma, float(np.sqrt(2.0 / curvature)) if curvature > 0 else float("nan")


def main(argv=None):
    args = check_arguments(__doc__.split("\n")[0], SPHERES_RUN_HELP, 1e-4,
                           "absolute agreement required of gamma (the two minimisers stop at different points)",
                           argv, kind="absolute")
    ok, compared = True, 0
    for section, run_path, run in analysed_runs(args.results, "late_decay", "late-decay", args.run):
        histograms = run.histograms
        if "tail_times" not in section.attrs:
            print(f"{run_path}: no histograms, nothing to compare")
            continue
        times = np.atleast_1d(section.attrs["tail_times"])
        if len(times) != len(histograms):
            print(f"{run_path}: C++ has {len(times)} histogram times, the run {len(histograms)} FAIL")
            ok = False
            continue
        for j, histogram in enumerate(histograms):
            gamma, sigma = refit(np.asarray(histogram.data["counts"], float), float(run.attrs["histogram_range"]))
            cpp_gamma = float(np.atleast_1d(section.attrs["tail_gamma"])[j])
            cpp_sigma = float(np.atleast_1d(section.attrs["tail_gamma_sigma"])[j])
            good = agree(cpp_gamma, gamma, args.tolerance, False) and agree(cpp_sigma, sigma, SIGMA_TOLERANCE, True)
            print(f"{run_path} t = {float(histogram.attrs['time']):g}: gamma {cpp_gamma:.6f} vs {gamma:.6f}, "
                  f"sigma {cpp_sigma:.5f} vs {sigma:.5f}  {'ok' if good else 'FAIL'}")
            ok &= good
            compared += 1
    print(f"{compared} histograms compared, {'all agree' if ok else 'DISAGREEMENT'}")
    return 0 if ok and compared > 0 else 1


if __name__ == "__main__":
    try:
        sys.exit(main())
    except (InputError, OSError, shockgas.SchemaError) as error:
        fail(error)
