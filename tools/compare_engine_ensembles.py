#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Two engines' ensembles of the same run, compared statistically.

    /usr/bin/python3 tools/compare_engine_ensembles.py A.h5 B.h5

    /usr/bin/python3 tools/compare_engine_ensembles.py --mechanisms ELASTIC.h5 STICKY.h5

A and B are shockgas-sim outputs of the same parameters made by two engines (for example --engine
event and --engine passthrough), with the same or with independent seeds. With --mechanisms they
may differ in the sub-threshold mechanism as well (elastic against sticky collisions below delta,
which the paper finds give the same T(t) and one Phi): then T(t) and the histograms are compared
and the collision count is not (the two count different events: sticky merges end the collisions
inside a cluster that elastic ones repeat).

The engines round differently and the dynamics is chaotic, so realizations part ways; what must agree is the
statistics:

  * T(t): the ensemble means differ by at most 3 sigma at every sample, sigma the standard error of
    the difference of the means over realizations; with few realizations, at most the |z| of the
    same probability under Welch's t law (fails());
  * collisions per particle at the last sample, the same way;
  * each stored histogram: per bin, the realizations' mean fraction in A and in B, compared with
    the standard error of the difference from the realization spread; the sum of the squared
    z-scores over bins with enough counts is compared with the same sum over random relabellings
    of the realizations between A and B (a permutation test, PERMUTATIONS of them, fixed seed),
    whose tail gives the p-value. The chi-square law's own p-value is printed beside it. It holds
    only for many realizations per file: each bin's error comes from the realizations' spread, so
    with R realizations a z-score is Student-t-like with R - 1 degrees of freedom, and with R = 4
    (Fig. 4's quick elastic runs) the sum is about twice its chi-square expectation when A and B
    have the same law (chi-square p < 1e-3 where the permutation test gives 0.07-0.6). (Particles of one realization are not independent samples: clusters move together,
    so a chi-square on pooled particle counts would reject equal laws.)

Prints one line per check and exits 1 if any check fails (|z| > 3, p < 1e-3, or a statistic that
is NaN: a sample no realization reached, or one reached by a single realization, has no standard
error and cannot pass).

Refused with exit status 2 and one line "compare_engine_ensembles.py: error: ..." on stderr, before
anything is compared: a command line other than A.h5 B.h5 (an unknown option, a name left out); a
file that is missing or not a shockgas-sim run; A and B whose physics parameters differ
(PHYSICS_PARAMETERS below; the seed, the engine, the first realization and the number of
realizations may differ: they are what is compared, or only change the error bars); different
sample times; different histogram times or bins; fewer than 2 realizations in either file (the
standard error needs two).
"""
import sys

SCRIPT = "compare_engine_ensembles.py"
try:
    import numpy as np
    from scipy import stats

    import shockgas_path  # noqa: F401  (python/ of this source tree on Python's path: tools/shockgas_path.py)
    import shockgas  # python/shockgas of this source tree, else the installed module
    from shockgas.cli import ArgumentParser, fail  # a user's mistake in one line, exit 2
except ImportError as error:  # pragma: no cover - depends on the machine
    print(f"{SCRIPT}: error: {error.name or error} is missing (needs numpy, scipy and h5py): "
          f"run it with Debian's /usr/bin/python3", file=sys.stderr)
    sys.exit(2)

# A disagreement of more than 3 standard errors at any of ~40 samples has probability ~1e-1 under the
# null for independent samples; the samples are correlated, so 3 sigma is the criterion.
Z_LIMIT = 3.0
# Histogram bins with fewer counts than this are merged into their neighbours' tails (chi-square
# needs ~5 expected counts per bin).
MIN_COUNTS = 20
P_LIMIT = 1e-3
# Relabellings of the realizations for the histograms' permutation test: its smallest p-value is
# 1 / (PERMUTATIONS + 1), well below P_LIMIT; a fixed seed makes the verdict reproducible.
PERMUTATIONS = 2000
PERMUTATION_SEED = 20261202
# A standard error needs at least two realizations.
MIN_REALIZATIONS = 2
# Root attributes that fix the physics and the sampling of a run (docs/cli-and-output.md). They must
# be equal in A and B wherever both files record them. Not compared: seed, engine,
# first_realization, realizations (the point of the comparison, or only the error bars), the
# provenance (program, version, compiler, date, host, timings), the outcome (status,
# total_collisions), and snapshot options (nothing here reads snapshots).
PHYSICS_PARAMETERS = ("particles", "ring_length", "restitution", "velocity_threshold", "subthreshold",
                      "collapse_speed", "positions", "velocity_distribution", "initial_condition",
                      "init_file_sha256", "t_max", "samples_per_decade", "sample_times",
                      "histogram_times", "histogram_bins", "histogram_range")


class InputError(Exception):
    """A user's mistake: the files cannot be compared (exit 2, one line)."""


def mean_and_error(values):
    """Mean and standard error over the realizations that reached the sample; NaN and NaN when
    none did, the mean and NaN when one did."""
    values = values[np.isfinite(values)]
    if len(values) == 0:
        return np.nan, np.nan
    if len(values) < 2:
        return float(values.mean()), np.nan
    return float(values.mean()), float(values.std(ddof=1) / np.sqrt(len(values)))


def z_score(ma, ea, mb, eb):
    """(ma - mb) / sqrt(ea^2 + eb^2); NaN when any input is; with no spread at all, 0 for equal
    means and inf for different ones (a difference without scatter is not a pass)."""
    error = np.hypot(ea, eb)
    if not np.isfinite(error) or not (np.isfinite(ma) and np.isfinite(mb)):
        return np.nan
    if error == 0:
        return 0.0 if ma == mb else np.inf
    return (ma - mb) / error


def welch_dof(a, b):
    """Welch-Satterthwaite degrees of freedom of the difference of two means, from the realizations
    that reached the sample (a, b); inf where either spread is zero or unknown (then the normal law)."""
    a, b = a[np.isfinite(a)], b[np.isfinite(b)]
    if len(a) < 2 or len(b) < 2:
        return np.inf
    va, vb = a.var(ddof=1) / len(a), b.var(ddof=1) / len(b)
    denominator = va * va / (len(a) - 1) + vb * vb / (len(b) - 1)
    return (va + vb) ** 2 / denominator if denominator > 0 else np.inf


def fails(z, dof=np.inf):
    """|z| beyond Z_LIMIT standard errors, where the standard errors come from the realizations
    themselves: with few realizations z is Student-t distributed (Welch), and the limit is the |z|
    of the same two-sided probability as Z_LIMIT under the normal law (3 sigma: 0.27%), so that 4
    realizations are not failed for the width of a t law with 3 degrees of freedom (|z| = 4.4 of
    two same-law sticky-gas ensembles). Many realizations: |z| > Z_LIMIT."""
    if not np.isfinite(z):
        return True
    if not np.isfinite(dof):
        return abs(z) > Z_LIMIT
    return 2.0 * stats.t.sf(abs(z), dof) < 2.0 * stats.norm.sf(Z_LIMIT)


def histogram_chi2(a, b):
    """Sum over bins of the squared z-score of the difference of the realizations' mean fractions,
    a and b (..., realizations, bins), the leading axes a batch of relabellings; a bin without
    spread adds nothing."""
    diff = a.mean(axis=-2) - b.mean(axis=-2)
    error = np.sqrt(a.var(axis=-2, ddof=1) / a.shape[-2] + b.var(axis=-2, ddof=1) / b.shape[-2])
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(error > 0, (diff / error) ** 2, 0.0).sum(axis=-1)


def permutation_p(fa, fb, observed):
    """The share of random relabellings of the realizations (A's count drawn from both, the rest
    B's) whose histogram_chi2 reaches the observed one, counting the observation itself."""
    rng = np.random.default_rng(PERMUTATION_SEED)
    rows = np.vstack([fa, fb])
    reached = 0
    batch = 100  # relabellings at a time: (batch x realizations x bins) doubles, tens of MB at most
    for start in range(0, PERMUTATIONS, batch):
        orders = np.argsort(rng.random((min(batch, PERMUTATIONS - start), len(rows))), axis=1)
        chi2 = histogram_chi2(rows[orders[:, :len(fa)]], rows[orders[:, len(fa):]])
        reached += int(np.sum(chi2 >= observed))
    return (reached + 1) / (PERMUTATIONS + 1)


def check_comparable(a_path, b_path, a, b, may_differ=()):
    """Raises InputError unless A and B are the same physics, sampled at the same times, apart from
    the parameters named in may_differ."""
    for path, run in ((a_path, a), (b_path, b)):
        if run.realizations < MIN_REALIZATIONS:
            raise InputError(f"{path}: {run.realizations} realization{'' if run.realizations == 1 else 's'}; the standard errors need at least "
                             f"{MIN_REALIZATIONS} in each file (shockgas-sim -R)")
    differ = [f"{name} {a.attrs[name]!r} vs {b.attrs[name]!r}" for name in PHYSICS_PARAMETERS
              if name not in may_differ and name in a.attrs and name in b.attrs and a.attrs[name] != b.attrs[name]]
    if differ:
        raise InputError(f"{a_path} and {b_path} are not the same run: {'; '.join(differ)}")
    if a.time.shape != b.time.shape or not np.array_equal(a.time, b.time):
        raise InputError(f"{a_path} and {b_path} have different sample times ({len(a.time)} from "
                         f"{a.time[0]:g} to {a.time[-1]:g} vs {len(b.time)} from {b.time[0]:g} to {b.time[-1]:g})")
    times_a = [float(np.asarray(h.time)) for h in a.histograms]
    times_b = [float(np.asarray(h.time)) for h in b.histograms]
    if times_a != times_b:
        raise InputError(f"{a_path} and {b_path} have different histogram times "
                         f"({', '.join(f'{t:g}' for t in times_a) or 'none'} vs "
                         f"{', '.join(f'{t:g}' for t in times_b) or 'none'})")
    for ha, hb, t in zip(a.histograms, b.histograms, times_a):
        if np.shape(ha.edges) != np.shape(hb.edges) or not np.array_equal(ha.edges, hb.edges):
            raise InputError(f"{a_path} and {b_path}: the histograms at t = {t:g} have different bins")


def compare(a, b, count_collisions=True):
    """Prints one line per check; True if every check passes."""
    ok = True
    worst, worst_t, undefined = 0.0, float(a.time[0]), []
    for k, t in enumerate(a.time):
        z = z_score(*mean_and_error(a.temperature[:, k]), *mean_and_error(b.temperature[:, k]))
        dof = welch_dof(a.temperature[:, k], b.temperature[:, k])
        if np.isnan(z):
            undefined.append(float(t))
        elif abs(z) >= abs(worst):
            worst, worst_t = z, float(t)
        ok &= not fails(z, dof)
    line = f"T(t): {len(a.time)} samples, largest |z| = {abs(worst):.2f} at t = {worst_t:g}"
    if undefined:
        line += (f"; FAIL: no standard error at {len(undefined)} samples (t = "
                 f"{', '.join(f'{t:g}' for t in undefined[:5])}{', ...' if len(undefined) > 5 else ''}): "
                 f"fewer than 2 realizations reached them")
    print(line)

    ma, ea = mean_and_error(a.collisions_per_particle[:, -1])
    mb, eb = mean_and_error(b.collisions_per_particle[:, -1])
    if count_collisions:
        z = z_score(ma, ea, mb, eb)
        dof = welch_dof(a.collisions_per_particle[:, -1], b.collisions_per_particle[:, -1])
        print(f"collisions per particle at t = {a.time[-1]:g}: {ma:.3f} +- {ea:.3f} vs {mb:.3f} +- {eb:.3f}, "
              f"z = {z:.2f}" + (" FAIL" if fails(z, dof) else ""))
        ok &= not fails(z, dof)
    else:
        print(f"collisions per particle at t = {a.time[-1]:g}: {ma:.3f} vs {mb:.3f}, not compared "
              f"(different sub-threshold mechanisms count different events)")

    for ha, hb in zip(a.histograms, b.histograms):
        counts_a = np.asarray(ha.counts, dtype=float)
        counts_b = np.asarray(hb.counts, dtype=float)
        with np.errstate(invalid="ignore", divide="ignore"):
            fa = counts_a / counts_a.sum(axis=1, keepdims=True)
            fb = counts_b / counts_b.sum(axis=1, keepdims=True)
        pooled = counts_a.sum(axis=0) + counts_b.sum(axis=0)
        diff = fa.mean(axis=0) - fb.mean(axis=0)
        error = np.sqrt(fa.var(axis=0, ddof=1) / len(fa) + fb.var(axis=0, ddof=1) / len(fb))
        keep = pooled >= MIN_COUNTS
        # A bin with no scatter in either ensemble has no error bar: it passes only if A and B agree
        # exactly there (both empty, typically), else the histograms differ without any noise.
        exact_mismatch = keep & (error == 0) & (diff != 0)
        keep &= error > 0
        chi2 = float(histogram_chi2(fa[:, keep], fb[:, keep]))
        dof = int(keep.sum())
        p_law = float(stats.chi2.sf(chi2, dof)) if dof > 0 else 1.0
        p = permutation_p(fa[:, keep], fb[:, keep], chi2) if dof > 0 else 1.0
        if exact_mismatch.any():
            p = 0.0
        bad = not np.isfinite(p) or p < P_LIMIT
        print(f"histogram t = {float(np.asarray(ha.time)):g}: chi2 = {chi2:.1f} for {dof} bins, p = {p:.3f} "
              f"(permutations; chi-square law {p_law:.3f})"
              + (f", {int(exact_mismatch.sum())} bins differ without scatter" if exact_mismatch.any() else "")
              + (" FAIL" if bad else ""))
        ok &= not bad
    return ok


def main(argv=None):
    parser = ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("a_path", metavar="A.h5", help="a shockgas-sim output")
    parser.add_argument("b_path", metavar="B.h5", help="one of the same parameters, by another engine or seed")
    parser.add_argument("--mechanisms", action="store_true",
                        help="A and B may differ in the sub-threshold mechanism (elastic, sticky): compare T(t) "
                             "and the histograms, not the collision count")
    args = parser.parse_args(argv)
    a_path, b_path = args.a_path, args.b_path
    a, b = shockgas.read_run(a_path), shockgas.read_run(b_path)
    check_comparable(a_path, b_path, a, b, may_differ=("subthreshold",) if args.mechanisms else ())
    if args.mechanisms:
        print(f"sub-threshold mechanisms: {a.attrs.get('subthreshold')} (A) and {b.attrs.get('subthreshold')} (B)")
    return 0 if compare(a, b, count_collisions=not args.mechanisms) else 1


if __name__ == "__main__":
    try:
        sys.exit(main())
    # The shockgas module's errors (a missing, unreadable or damaged file, one of another kind) say
    # "<path>: <what>" already: the user's, like InputError.
    except (InputError, OSError, shockgas.SchemaError) as error:
        fail(error)
