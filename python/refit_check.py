#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
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
  * sigma: delete-one jackknife over realizations, each replica the whole weighted fit on the other
    n - 1 realizations (their mean and their SE(T_k)), sqrt((n-1)/n sum (theta_i - mean theta)^2);
  * an SE not above 1e-12 <T>_k (identical realizations, or a single one) gives equal weights:
    sigma_k = 1.
With one realization there is no jackknife and no standard error to weight by: the C++ prints
"+- n/a" and stores exponent_sigma and chi2_per_dof NaN; then the exponent (an unweighted fit) is
compared and the other two are reported as n/a (they agree when both sides give none). Two
realizations are treated the same way: a standard error from two values (one degree
of freedom) is no weight, and the jackknife's two one-realization replicas give a sigma of one degree
of freedom, so the C++ fits unweighted and stores both NaN.

The run: --run RUN.h5, else the results file's `input_path`. That path is as it was given to
shockgas-analyze, relative to wherever it ran, so a relative one is looked for next to the results
file first, then in the current directory. The run found must be the one the results were computed
from: every root attribute the results file copied from its input (input_<name>: seed, date,
total_collisions, parameters, provenance) must equal the run's; a run that differs in any is refused,
naming the attribute (another run.h5 in the current directory, a rerun with another seed, ...).

Exit status 0 when exponent, exponent_sigma and chi2_per_dof agree within the relative tolerance,
1 otherwise, 2 with one line "refit_check.py: error: ..." on stderr for bad input (a missing file, a
file that is not a decay results file, a run that is not the analysed one, a bad --tolerance, the
shockgas module not on Python's path), 77 (SKIP, for ctest's SKIP_RETURN_CODE) when numpy, scipy or
h5py is missing, named on stdout.
"""
import os
import sys

SKIP = 77
try:
    import h5py  # noqa: F401  (the shockgas module's; imported here to be named when missing)
    import numpy as np
    from scipy import optimize
except ImportError as error:  # pragma: no cover - depends on the machine
    # A machine without the packages: ctest's python.refit_check skips (SKIP_RETURN_CODE 77).
    print("SKIP: refit_check.py needs numpy, scipy and h5py: %s is missing; run it with Debian's /usr/bin/python3 "
          "(python3-numpy, python3-scipy, python3-h5py)" % (error.name or error))
    sys.exit(SKIP)
try:
    import shockgas  # python/shockgas: this script's folder in the source tree, else the installed module
    from shockgas.cli import ArgumentParser, fail  # a user's mistake in one line, exit status 2
except ImportError as error:
    # Not a skip: the module is not beside this script (an installed copy in share/shockgas/python, the
    # module installed at another prefix), or it does not import. In the source tree it is always
    # beside the script: a broken module fails ctest's python.refit_check rather than skip it.
    if error.name == "shockgas":
        why = ("the Python module shockgas is missing (not beside this script, nor on Python's path): set "
               "PYTHONPATH to the folder `cmake --install` put it in (such as <prefix>/lib/python%d.%d/site-packages; "
               "docs/python.md), or run the source tree's python/refit_check.py" % sys.version_info[:2])
    else:
        why = "the Python module shockgas does not import (%s): another version of it on Python's path?" % error
    print("refit_check.py: error: %s" % why, file=sys.stderr)
    sys.exit(2)


def weighted_slope(x, y, sigma):
    """Straight line y = a + b x by weighted least squares (scipy), returns (b, chi2)."""
    popt, _ = optimize.curve_fit(lambda xx, a, b: a + b * xx, x, y, p0=(y[0], 0.0), sigma=sigma,
                                 absolute_sigma=True, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15)
    a, b = popt
    chi2 = float(np.sum(((y - a - b * x) / sigma) ** 2))
    return float(b), chi2


class InputError(Exception):
    """A user's mistake (exit 2, one line)."""


def refit(run, t_lo, t_hi):
    """The C++ estimator redone with scipy on a Run, in the decay fit's window [t_lo, t_hi]."""
    time, temperature = run.time, run.temperature           # K; R x K
    every = np.all(np.isfinite(temperature) & (temperature > 0), axis=0)
    inside = every & (time >= t_lo * (1 - 1e-12)) & (time <= t_hi * (1 + 1e-12))
    t = time[inside]
    T = temperature[:, inside]
    R = T.shape[0]
    if len(t) < 3:
        raise InputError(f"{run.file}: {len(t)} sample times in the window [{t_lo:g}, {t_hi:g}] reached by every "
                         f"realization; the decay fit had more: this is not the analysed run")
    x = np.log(t)

    # Fewer than this many realizations: the fit is unweighted (equal weights), as in the C++.
    fewest_to_weigh = 3

    def fit(rows):
        """-slope and chi2 of the weighted fit on these realizations (rows of T)."""
        n = rows.shape[0]
        mean = rows.mean(axis=0)
        se = rows.std(axis=0, ddof=1) / np.sqrt(n) if n >= 2 else np.zeros_like(mean)
        # No scatter above rounding (identical realizations, or one): equal weights, as the C++ does.
        se = np.where(se > 1e-12 * mean, se, mean)
        if R < fewest_to_weigh:  # the whole run's rule, in every replica too
            se = mean
        slope, chi2 = weighted_slope(x, np.log(mean), se / mean)   # d ln y = dy / y
        return -slope, chi2

    exponent, chi2 = fit(T)
    if R < fewest_to_weigh:  # one realization, nothing to leave out; two, one degree of freedom: "+- n/a"
        jack_sigma = float("nan")
    else:
        jack = np.array([fit(np.delete(T, i, axis=0))[0] for i in range(R)])
        jack_sigma = float(np.sqrt((R - 1) / R * np.sum((jack - jack.mean()) ** 2)))
    # Unweighted (one or two realizations): chi2 has no meaning (the C++ stores NaN).
    chi2_per_dof = chi2 / (len(t) - 2) if R >= fewest_to_weigh else float("nan")
    return dict(exponent=exponent, exponent_sigma=jack_sigma, chi2_per_dof=chi2_per_dof, points=len(t),
                realizations=R)


def _same(a, b):
    """Attribute equality as stored: exact, NaN equal to NaN, arrays element by element."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        if a.shape != b.shape:
            return False
        if a.dtype.kind in "fc" and b.dtype.kind in "fc":
            return bool(np.array_equal(a, b, equal_nan=True))
        return bool(np.array_equal(a, b))
    if isinstance(a, float) and isinstance(b, float) and a != a and b != b:
        return True
    return a == b


def provenance_mismatch(recorded, run_attrs):
    """The first recorded input attribute (results' input_<name>) the run does not carry with the same
    value, as text; None when the run is the analysed one."""
    first = ("seed", "date", "total_collisions")  # the likeliest to tell another run apart: named first
    for name in sorted(recorded, key=lambda n: (first.index(n) if n in first else len(first), n)):
        if name == "path":
            continue
        if name not in run_attrs:
            return f"it has no attribute {name} (the analysed run had {recorded[name]!r})"
        if not _same(recorded[name], run_attrs[name]):
            return f"its {name} is {run_attrs[name]!r}, the analysed run's was {recorded[name]!r}"
    return None


def find_run(results_path, recorded, given):
    """The analysed run: `given` (--run) or the recorded input_path, looked for next to the results
    file first, then as it stands (the current directory); refused unless its attributes are the
    recorded ones."""
    if given:
        candidates = [given]
    else:
        recorded_path = recorded.get("path")
        if not recorded_path:
            raise InputError(f"{results_path}: no input_path recorded; name the run with --run RUN.h5")
        if os.path.isabs(recorded_path):
            candidates = [recorded_path]
        else:
            beside = os.path.join(os.path.dirname(os.path.abspath(results_path)), recorded_path)
            candidates = [beside] + ([recorded_path] if os.path.abspath(recorded_path) != beside else [])
    refused = []
    for candidate in candidates:
        if not os.path.exists(candidate):
            continue
        run = shockgas.read_run(candidate)
        why = provenance_mismatch(recorded, run.attrs)
        if why is None:
            return candidate, run
        refused.append(f"{candidate}: {why}")
    if refused:
        raise InputError(f"{results_path} was not computed from {'; nor from '.join(refused)}"
                         + ("" if given else "; name the analysed run with --run RUN.h5"))
    raise InputError(f"{results_path}: its input {candidates[0] if given else recorded.get('path')!r} is not found "
                     f"(looked for {' and '.join(candidates)}); name it with --run RUN.h5")


def analysed_runs(results_path, prefix, command, given=None):
    """(section, run path, run) for each input k of a shockgas-analyze results file with a section /<prefix><k>
    per input (clusters, late-decay), each run found and checked by find_run; refuses a file without
    /<prefix>0, and --run (given) when there is more than one input."""
    results = shockgas.read_results(results_path)
    inputs = results.inputs()
    if f"{prefix}0" not in results.sections:
        raise InputError(f"{results_path}: no /{prefix}0 section: not a shockgas-analyze {command} results file "
                         f"({results.attrs.get('program')})")
    if given and len(inputs) != 1:
        raise InputError(f"--run names one run; {results_path} has {len(inputs)} inputs")
    return [(results.sections[f"{prefix}{k}"], *find_run(results_path, recorded, given))
            for k, recorded in enumerate(inputs)]


def agree(cpp, py, tolerance, relative=True):
    """Whether the C++ and the Python number agree within tolerance, relative to the larger or absolute;
    a missing number (NaN) agrees only with a missing one."""
    if cpp != cpp or py != py:
        return (cpp != cpp) and (py != py)
    return cpp == py or abs(cpp - py) <= (tolerance * max(abs(cpp), abs(py)) if relative else tolerance)


# --run's help in the checks of shockgas-spheres analyses (clusters_check.py, tails_check.py).
SPHERES_RUN_HELP = "shockgas-spheres output (one input only; default: the recorded input_path)"


def check_arguments(description, run_help, tolerance, tolerance_help, argv=None, kind="relative"):
    """The arguments of every check script: the results file, --run and --tolerance, refused (InputError)
    unless finite and >= 0."""
    ap = ArgumentParser(description=description)
    ap.add_argument("results")
    ap.add_argument("--run", help=run_help)
    ap.add_argument("--tolerance", type=float, default=tolerance, help=tolerance_help)
    args = ap.parse_args(argv)
    if not (args.tolerance >= 0 and np.isfinite(args.tolerance)):
        raise InputError(f"--tolerance {args.tolerance!r}: a finite {kind} tolerance >= 0")
    return args


def fmt(value):
    return "n/a" if value != value else "%.12g" % value


def main(argv=None):
    args = check_arguments(__doc__.split("\n")[0], "simulation output (default: the results file's input_path)",
                           1e-6, "relative agreement required", argv)
    results = shockgas.read_results(args.results)
    if "decay" not in results.sections:
        raise InputError(f"{args.results}: no /decay section: not a shockgas-analyze decay results file "
                         f"({results.attrs.get('program')})")
    inputs = results.inputs()
    if len(inputs) != 1:
        raise InputError(f"{args.results}: {len(inputs)} inputs recorded; a decay fit has one")
    decay = results["decay"].attrs
    try:
        cpp = {k: float(decay[k]) for k in ("exponent", "exponent_sigma", "chi2_per_dof", "t_lo", "t_hi")}
    except KeyError as missing:
        raise InputError(f"{args.results}: /decay has no attribute {missing}") from None
    run_path, run = find_run(args.results, inputs[0], args.run)
    py = refit(run, cpp["t_lo"], cpp["t_hi"])
    ok = True
    for key in ("exponent", "exponent_sigma", "chi2_per_dof"):
        c, p = cpp[key], py[key]
        if c != c or p != p:  # n/a: one realization has no jackknife sigma and no weights for chi2
            good = (c != c) and (p != p)
            note = ("n/a on both sides (%d realization%s: no jackknife, no weights)"
                    % (py["realizations"], "" if py["realizations"] == 1 else "s") if good else "n/a on one side only")
            print("%-15s C++ %s  scipy %s  %s %s" % (key, fmt(c), fmt(p), note, "ok" if good else "FAIL"))
        else:
            rel = abs(p - c) / abs(c) if c != 0 else abs(p - c)
            good = rel <= args.tolerance
            print("%-15s C++ %.12g  scipy %.12g  relative difference %.2e %s" % (key, c, p, rel,
                                                                                 "ok" if good else "FAIL"))
        ok &= good
    print("window [%g, %g], %d points, %d realization%s, run %s (seed %s, made %s: the analysed run)"
          % (cpp["t_lo"], cpp["t_hi"], py["points"], py["realizations"], "" if py["realizations"] == 1 else "s",
             run_path, run.attrs.get("seed"), run.attrs.get("date")))
    return 0 if ok else 1


if __name__ == "__main__":
    try:
        sys.exit(main())
    # The shockgas module's errors (a missing, unreadable or damaged file, one of another kind) say
    # "<path>: <what>" already: the user's, like InputError.
    except (InputError, OSError, shockgas.SchemaError) as error:
        fail(error)
