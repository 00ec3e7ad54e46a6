#!/usr/bin/env python3
"""Two engines' ensembles of the same run, compared statistically.

    tools/compare_engine_ensembles.py A.h5 B.h5

A and B are shockgas-sim outputs of the same parameters and seeds made by two engines (for example
--engine event and --engine passthrough). The engines round differently and the dynamics is chaotic,
so realizations part ways; what must agree is the statistics:

  * T(t): the ensemble means differ by at most 3 sigma at every sample, sigma the standard error of
    the difference of the means over realizations;
  * collisions per particle at the last sample, the same way;
  * each stored histogram: per bin, the realizations' mean fraction in A and in B, compared with
    the standard error of the difference from the realization spread; the sum of the squared
    z-scores over bins with enough counts is a chi-square with one degree of freedom per bin,
    giving its p-value. (Particles of one realization are not independent samples: clusters move
    together, so a chi-square on pooled particle counts would reject equal laws.)

Prints one line per check and exits 1 if any check fails (|z| > 3 or p < 1e-3).
"""
import sys

import numpy as np
from scipy import stats

sys.path.insert(0, __file__.rsplit("/tools/", 1)[0] + "/python")
import shockgas  # noqa: E402

# A disagreement of more than 3 standard errors at any of ~40 samples has probability ~1e-1 under the
# null for independent samples; the samples are correlated, so 3 sigma is the criterion.
Z_LIMIT = 3.0
# Histogram bins with fewer counts than this are merged into their neighbours' tails (chi-square
# needs ~5 expected counts per bin).
MIN_COUNTS = 20
P_LIMIT = 1e-3


def mean_and_error(values):
    values = values[np.isfinite(values)]
    return values.mean(), values.std(ddof=1) / np.sqrt(len(values))


def main(a_path, b_path):
    a, b = shockgas.read_run(a_path), shockgas.read_run(b_path)
    failed = False
    worst = (0.0, float(a.time[0]))
    for k, t in enumerate(a.time):
        ma, ea = mean_and_error(a.temperature[:, k])
        mb, eb = mean_and_error(b.temperature[:, k])
        z = (ma - mb) / np.hypot(ea, eb) if np.hypot(ea, eb) > 0 else 0.0
        if abs(z) > abs(worst[0]):
            worst = (z, t)
        failed |= abs(z) > Z_LIMIT
    print(f"T(t): {len(a.time)} samples, largest |z| = {abs(worst[0]):.2f} at t = {worst[1]:g}")
    ma, ea = mean_and_error(a.collisions_per_particle[:, -1])
    mb, eb = mean_and_error(b.collisions_per_particle[:, -1])
    z = (ma - mb) / np.hypot(ea, eb)
    print(f"collisions per particle at t = {a.time[-1]:g}: {ma:.3f} +- {ea:.3f} vs {mb:.3f} +- {eb:.3f}, z = {z:.2f}")
    failed |= abs(z) > Z_LIMIT
    for ha, hb in zip(a.histograms, b.histograms):
        fa = np.asarray(ha.counts, dtype=float)
        fb = np.asarray(hb.counts, dtype=float)
        fa = fa / fa.sum(axis=1, keepdims=True)
        fb = fb / fb.sum(axis=1, keepdims=True)
        pooled = np.asarray(ha.counts).sum(axis=0) + np.asarray(hb.counts).sum(axis=0)
        keep = pooled >= MIN_COUNTS
        diff = fa.mean(axis=0) - fb.mean(axis=0)
        error = np.sqrt(fa.var(axis=0, ddof=1) / len(fa) + fb.var(axis=0, ddof=1) / len(fb))
        keep &= error > 0
        chi2 = float(np.sum((diff[keep] / error[keep]) ** 2))
        dof = int(keep.sum())
        p = float(stats.chi2.sf(chi2, dof)) if dof > 0 else 1.0
        print(f"histogram t = {float(np.asarray(ha.time)):g}: chi2 = {chi2:.1f} for {dof} bins, p = {p:.3f}")
        failed |= p < P_LIMIT
    return 1 if failed else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2]))
