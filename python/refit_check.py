#!/usr/bin/python3
"""Refit the decay exponent of a shockgas-analyze `decay` results file with scipy, independently of
the C++ (GSL) code, and check agreement.

    /usr/bin/python3 python/refit_check.py DECAY_RESULTS.h5 [--run RUN.h5] [--tolerance 1e-6]

Reads /decay (exponent, exponent_sigma, t_lo, t_hi, chi2_per_dof) and the simulation output named by
the root attribute `input_path` (or --run). Estimator (analysis/src/temperature.cpp, fit.cpp):
  * sample times reached by every realization (T finite and > 0 in every row), inside [t_lo, t_hi]
    (ends widened by 1e-12 relative);
  * y_k = ln <T>_k, x_k = ln t_k, sigma_k = SE(T_k)/<T_k>, SE = sample std (n-1) / sqrt(n);
  * weighted least squares with weights 1/sigma_k^2 (scipy.optimize.curve_fit, absolute_sigma=True);
    exponent = -slope; chi2/dof = sum(residual^2/sigma^2)/(K-2);
  * sigma: delete-one jackknife over realizations, with the full-sample SE(T_k) divided by the
    delete-one mean (what fit_power_law does with the replica's y),
    sqrt((n-1)/n sum (theta_i - mean theta)^2).
Exit status 0 when exponent, exponent_sigma and chi2_per_dof agree within the relative tolerance,
1 otherwise, 77 (SKIP) when numpy/scipy/h5py are missing.
"""
import argparse
import os
import sys

SKIP = 77
try:
    import numpy as np
    from scipy import optimize

    import shockgas  # python/shockgas: this script's folder in the source tree, else the installed module
except ImportError as error:  # pragma: no cover - depends on the machine
    print("SKIP: refit_check.py needs numpy, scipy and h5py (%s); run with Debian's /usr/bin/python3" % error)
    sys.exit(SKIP)


def weighted_slope(x, y, sigma):
    """Straight line y = a + b x by weighted least squares (scipy), returns (b, chi2)."""
    popt, _ = optimize.curve_fit(lambda xx, a, b: a + b * xx, x, y, p0=(y[0], 0.0), sigma=sigma,
                                 absolute_sigma=True, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15)
    a, b = popt
    chi2 = float(np.sum(((y - a - b * x) / sigma) ** 2))
    return float(b), chi2


def refit(run_path, t_lo, t_hi):
    run = shockgas.read_run(run_path)
    time, temperature = run.time, run.temperature           # K; R x K
    every = np.all(np.isfinite(temperature) & (temperature > 0), axis=0)
    inside = every & (time >= t_lo * (1 - 1e-12)) & (time <= t_hi * (1 + 1e-12))
    t = time[inside]
    T = temperature[:, inside]
    R = T.shape[0]
    mean = T.mean(axis=0)
    se = T.std(axis=0, ddof=1) / np.sqrt(R) if R >= 2 else mean.copy()
    se = np.where(se > 0, se, mean)     # no scatter: equal weights, as the C++ does
    sigma = se / mean                    # d ln y = dy / y
    x = np.log(t)
    slope, chi2 = weighted_slope(x, np.log(mean), sigma)
    exponent = -slope
    # fit_power_law divides the absolute SE by the y it is given: in a jackknife replica that is
    # the delete-one mean, so sigma_k = SE_k / <T>_(i),k there (SE_k from the full sample).
    replicas = [np.delete(T, i, axis=0).mean(axis=0) for i in range(R)]
    jack = np.array([-weighted_slope(x, np.log(m), se / m)[0] for m in replicas])
    jack_sigma = float(np.sqrt((R - 1) / R * np.sum((jack - jack.mean()) ** 2)))
    return dict(exponent=exponent, exponent_sigma=jack_sigma, chi2_per_dof=chi2 / (len(t) - 2), points=len(t))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("results")
    ap.add_argument("--run", help="simulation output (default: the results file's input_path)")
    ap.add_argument("--tolerance", type=float, default=1e-6, help="relative agreement required")
    args = ap.parse_args(argv)
    results = shockgas.read_results(args.results)
    run = args.run or results.attrs["input_path"]
    decay = results["decay"].attrs
    cpp = {k: float(decay[k]) for k in ("exponent", "exponent_sigma", "chi2_per_dof", "t_lo", "t_hi")}
    if not os.path.exists(run):  # input_path is as given to shockgas-analyze: maybe relative to it
        run = os.path.join(os.path.dirname(os.path.abspath(args.results)), run)
    py = refit(run, cpp["t_lo"], cpp["t_hi"])
    ok = True
    for key in ("exponent", "exponent_sigma", "chi2_per_dof"):
        rel = abs(py[key] - cpp[key]) / abs(cpp[key])
        good = rel <= args.tolerance
        ok &= good
        print("%-15s C++ %.12g  scipy %.12g  relative difference %.2e %s" % (key, cpp[key], py[key], rel,
                                                                             "ok" if good else "FAIL"))
    print("window [%g, %g], %d points, run %s" % (cpp["t_lo"], cpp["t_hi"], py["points"], run))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
