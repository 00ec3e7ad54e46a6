#!/usr/bin/python3
"""python/sticky_pav.py's ensemble comparison on small inputs (ctest python.sticky_pav_inputs, label
python; about 8 s of CPU, most of it the exact theory's constants).

    test_sticky_pav_cli.py WORK_DIR

  * --hist-dir with a time below ~55: the mass bins (M_EDGES moved to half-integer masses) number
    fewer at t = 10 than at t = 100, and the per-realization histograms were stacked into one array
    (ValueError: inhomogeneous shape). Now each time has its own: the files for t = 10 and t = 100
    are written, with fewer bins at t = 10.
  * --hist-dir's chi2 with 2 realizations. Each bin's error bar was the standard error of the two
    realizations' values: one degree of freedom, so (mean - theory)/error has a Cauchy law; bins
    where both held the same count had an error of 0 (chi2 "inf") or of rounding size (5.6e28), and
    those left out, Phi, which agrees with the exact theory (below), still gave chi2/bins of 915 for
    N = 20000, seed 3 (91248/29 at t = 100), and 9 to 4000 (median 93) over 200 seed pairs. The
    error bar is now the counting error of the mean (each cluster one count of its weight), which
    needs no spread: chi2/bins of Phi over t = 100 to 800 is 1.00 here, 0.6 to 2.3 (median 1.01)
    over those 200 pairs; it must stay below PHI_CHI2_PER_BIN_CEILING. histogram_chi2 itself is
    checked on histograms drawn from a known law with 2 realizations: chi2/bins 0.975 for counts,
    1.12 for exponential weights (their squares estimated from few clusters per bin), where the
    scatter of the two gives inf and 47; and an error bar where both hold the same counts.
  * --compare with one or two --times fitted r_inf + a t^(-1/3) with "dof -1" (or 0) and errors of
    1e6: refused, exit 2, one line; so are one realization with --compare, a time the periodic copies
    cannot reach (a traceback before; the line names the --copies needed) and a time <= 0.
"""
import math
import os
import re
import shutil
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
import script_checks as sc  # noqa: E402

try:
    import numpy  # noqa: F401
    import scipy  # noqa: F401
except ImportError as error:  # pragma: no cover
    print("SKIP: needs numpy and scipy (%s)" % error)
    sys.exit(77)

WORK = sys.argv[1]
del sys.argv[1]
TOOL = sc.script("python", "sticky_pav.py")
NAME = "sticky_pav.py"
sys.path.insert(0, sc.script("python"))
import sticky_pav  # noqa: E402

# Phi from the exact sticky gas (N = 20000) agrees with the exact theory at t = 100..800 at the
# precision of two realizations: with counting errors, chi2/bins over those times lies in 0.6..2.3
# (median 1.01, 99% below 1.8) for 200 pairs of seeds; the scatter of two gave 9 to 3000, median 93.
PHI_CHI2_PER_BIN_CEILING = 2.5
# Every chi2 printed must be finite and below this (F(m) at t = 10, far from the t -> infinity
# theory, is the largest: 7.7e3 for 12 bins).
CHI2_CEILING = 1e5


def pav(*arguments):
    return sc.run([sc.PYTHON, TOOL, *arguments], cwd=WORK)


class Histograms(unittest.TestCase):
    def test_small_times_and_two_realizations(self):
        hist = os.path.join(WORK, "hist")
        shutil.rmtree(hist, ignore_errors=True)
        result = pav("--N", 20000, "--realizations", 2, "--seed", 3, "--times", 10, 100, 200, 400, 800,
                     "--compare", "--hist-dir", hist)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr[-3000:])
        lines = [line for line in result.stdout.splitlines() if line.startswith("# t = ")]
        self.assertEqual(len(lines), 5, result.stdout)
        phi_chi2 = phi_bins = 0
        for line in lines:
            values = re.findall(r"(\S+)/(\d+)", line)
            self.assertEqual(len(values), 4, line)  # Phi, F(m), F(m) without its first bin, m F(m)
            for chi2, bins in values:
                self.assertNotEqual(chi2, "n/a", line)
                self.assertTrue(math.isfinite(float(chi2)) and float(chi2) < CHI2_CEILING, line)
                self.assertGreater(int(bins), 0, line)
            if float(re.match(r"# t = (\S+):", line).group(1)) >= 100:
                phi_chi2 += float(values[0][0])
                phi_bins += int(values[0][1])
        self.assertLess(phi_chi2 / phi_bins, PHI_CHI2_PER_BIN_CEILING, result.stdout)

        def bins(name):
            with open(os.path.join(hist, name)) as handle:
                return sum(1 for line in handle if not line.startswith("#"))
        self.assertLess(bins("mass_number_t10.dat"), bins("mass_number_t100.dat"))
        self.assertEqual(bins("phi_t10.dat"), bins("phi_t100.dat"))  # z bins do not depend on t


class ErrorBars(unittest.TestCase):
    """sticky_pav.histogram_chi2 on histograms drawn from a known law: K clusters per realization,
    each in bin b with probability p_b (a Gaussian over 40 bins), of weight w / K, the density of a
    bin the sum of its weights, whose expectation, the theory, is p_b: weights 1 (counts, as F(m))
    or exponential of mean 1 (masses, as Phi and m F(m))."""

    TRIALS, CLUSTERS = 400, 2000

    def hist(self, rng, p, masses, realizations=2):
        parts = []
        for _ in range(realizations):
            bins = rng.choice(len(p), size=self.CLUSTERS, p=p)
            w = (rng.exponential(1.0, size=self.CLUSTERS) if masses else numpy.ones(self.CLUSTERS)) / self.CLUSTERS
            parts.append((numpy.bincount(bins, weights=w, minlength=len(p)),
                          numpy.bincount(bins, weights=w * w, minlength=len(p)), numpy.bincount(bins, minlength=len(p))))
        return {name: numpy.array([part[i] for part in parts]) for i, name in enumerate(sticky_pav.HISTOGRAM_PARTS)}

    def chi2_per_bin(self, masses):
        """chi2/bins of histogram_chi2 over all trials, and the median over trials of chi2/bins with
        the error bar from the two realizations' scatter (what the script did before)."""
        rng = numpy.random.default_rng(11)
        x = numpy.linspace(-3, 3, 40)
        p = numpy.exp(-x * x / 2)
        p /= p.sum()
        chi2 = bins = 0
        scatter = []
        for _ in range(self.TRIALS):
            hist = self.hist(rng, p, masses)
            mean, error, z, use = sticky_pav.histogram_chi2(hist, p)
            chi2 += float(numpy.sum(z ** 2))
            bins += int(use.sum())
            spread = hist["density"].std(axis=0, ddof=1) / math.sqrt(2)
            with numpy.errstate(divide="ignore"):  # two equal counts: no spread, chi2 inf (as it printed)
                scatter.append(float(numpy.mean(((mean - p)[use] / spread[use]) ** 2)))
        return chi2 / bins, float(numpy.median(scatter))

    def test_counts(self):
        # ~33 bins x 400 trials: a standard deviation of ~0.012 around 1 - 1/33 (multinomial: the
        # bins share the K clusters), 0.975 here. From the scatter of two, chi2/bins is infinite in
        # most trials (a bin where both realizations hold the same count), 47 (median) with masses.
        counting, scatter = self.chi2_per_bin(masses=False)
        self.assertAlmostEqual(counting, 1.0, delta=0.06)
        self.assertGreater(scatter, 5.0)

    def test_masses(self):
        # The squared weights are estimated from each bin's own clusters (10 to 200 here): with
        # weights as broad as an exponential's this puts chi2/bins ~10% high (1.12; 1.07 with ten
        # times the clusters), the price of an error bar that needs no spread.
        counting, scatter = self.chi2_per_bin(masses=True)
        self.assertTrue(0.95 < counting < 1.2, counting)
        self.assertGreater(scatter, 5.0)

    def test_realizations_holding_the_same_counts_still_have_an_error_bar(self):
        rng = numpy.random.default_rng(5)
        p = numpy.full(20, 1 / 20)
        one = self.hist(rng, p, masses=True, realizations=1)
        hist = {name: numpy.concatenate([value, value]) for name, value in one.items()}
        mean, error, z, use = sticky_pav.histogram_chi2(hist, p)
        self.assertTrue(use.all())
        self.assertTrue(numpy.all(error > 0) and numpy.all(numpy.isfinite(z)))
        numpy.testing.assert_allclose(error, numpy.sqrt(2 * one["sumw2"][0]) / 2)


class Refusals(unittest.TestCase):
    def test_a_fit_needs_three_times(self):
        for times in ([100], [100, 200], [100, 100, 200]):
            sc.one_line_error(self, pav("--N", 2000, "--realizations", 3, "--times", *times, "--compare"), NAME,
                              "3 or more different --times")

    def test_compare_needs_two_realizations(self):
        sc.one_line_error(self, pav("--N", 2000, "--realizations", 1, "--times", 100, 200, 300, "--compare"), NAME,
                          "--realizations 2 or more")

    def test_a_time_past_the_copies(self):
        # N = 2000 on a ring of L = 2000: t = 1e5 needs copies > 2 t max|v| / L = 100 max|v|, and
        # max|v| of 2000 uniform velocities on [-1, 1] less their mean lies in [0.99, 1.05]
        # (the mean of 2000 is within +-0.05 at 3.8 sigma): 100 to 106 copies.
        line = sc.one_line_error(self, pav("--N", 2000, "--realizations", 2, "--times", 100, 100000), NAME,
                                 "t = 100000 too large for 1 copies", "--copies")
        needed = int(re.search(r"--copies (\d+) or more", line).group(1))
        self.assertTrue(100 <= needed <= 106, line)

    def test_times_must_be_positive(self):
        sc.one_line_error(self, pav("--N", 2000, "--times", 0, 100), NAME, "> 0")


if __name__ == "__main__":
    os.makedirs(WORK, exist_ok=True)
    unittest.main(verbosity=2)
