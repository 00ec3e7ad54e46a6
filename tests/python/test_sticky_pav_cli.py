#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""python/sticky_pav.py's ensemble comparison on small inputs (ctest python.sticky_pav_inputs, label
python; about 17 s of CPU, most of it the exact theory's constants, computed by each of the two
--compare runs through the command line; the other runs call main() with them given, CONSTANTS).

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
  * --compare's fit with two realizations: its error bars, the standard errors from their spread,
    have one degree of freedom (chi2/dof without a finite mean), and where both realizations held
    the same number of clusters (N = 2000, seed 1, t = 400) an error of 0 killed the fit with a
    LinAlgError traceback. Below MIN_FIT_REALIZATIONS (5) the fit is now n/a, saying why, and the
    table is printed all the same; with 5, a time at which every realization holds the same value
    (no collision yet at t = 0.001) makes that fit n/a, naming the time (a traceback before), the
    other fit and --json unharmed. fit_finite_time is checked directly too.
  * --compare's +- of r_inf and a was the fit's own width, which takes the times of one realization
    as independent: about half the spread of r_inf over independent ensembles (N = 2000, R = 10, 9
    times from 10 to 400, 100 ensembles with fixed seeds: 0.54 for T, 0.62 for n). It is now the
    jackknife over realizations, 0.94 and 1.02 of that spread (the fit's width still printed beside).
  * an output that cannot be written (--json, --hist-dir, --clusters-out into a missing directory,
    under a file, a directory given for a file, a read-only directory when not run as root): a
    traceback after the whole run before; now one line naming the option, the path and the cause,
    before any realization is run (the one stderr line is the error). Written to /dev/full (a full
    disk): --clusters-out exited 0 having written nothing (its file was never closed), --json gave a
    traceback; now one line "No space left on device".
  * --init given an HDF5 file (shockgas-sim's --init format, shockgas.write_initial_condition) said
    "'utf-8' codec can't decode byte 0x89": now it reads it (shockgas.read_initial_condition), with
    the same clusters as the same start written as text. Positions outside [0, L) (0..9 with --L 5) were unrolled into the wrong periodic copies and
    their particles missing from the clusters printed (exit 0): now refused, naming the first. An
    empty --init file (or comments alone) printed numpy's "input contained no data" warning above
    the error line: now the error line alone. An HDF5 start whose ring_length is an array, whose
    position is a group (TypeError tracebacks from shockgas.read_initial_condition) or a 2-D dataset:
    one line naming the item and what is wrong with it, exit 2 (script_checks.MALFORMED_STARTS).
"""
import contextlib
import io
import json
import math
import os
import re
import shutil
import unittest
from unittest import mock

import script_checks as sc

numpy, _ = sc.require("numpy", "scipy")

WORK = sc.arguments(1)
TOOL = sc.script("python", "sticky_pav.py")
NAME = "sticky_pav.py"
import exact_ballistic  # noqa: E402
import sticky_pav  # noqa: E402

# Phi from the exact sticky gas (N = 20000) agrees with the exact theory at t = 100..800 at the
# precision of two realizations: with counting errors, chi2/bins over those times lies in 0.6..2.3
# (median 1.01, 99% below 1.8) for 200 pairs of seeds; error bars from the scatter of two give 9 to
# 3000, median 93.
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
        for key, text in fit_lines(self, result.stdout).items():  # two realizations: no fit (FiniteTimeFit)
            self.assertTrue(text.startswith("n/a ("), text)
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
    # Counting errors: chi2/bins of plain counts has sd ~0.012 over the trials around 1 - 1/33 (the
    # bins share the clusters), so 0.06 is 5 sd; with mass weights it runs ~10% high (test_masses),
    # hence a one-sided 1.2 above and 0.95 below. The scatter of two realizations, which these error
    # bars replaced, gives a median above 5 (47 with masses, infinite in most plain trials).
    COUNTS_DELTA = 0.06
    MASSES_RANGE = (0.95, 1.2)
    SCATTER_FLOOR = 5.0

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
        self.assertAlmostEqual(counting, 1.0, delta=self.COUNTS_DELTA)
        self.assertGreater(scatter, self.SCATTER_FLOOR)

    def test_masses(self):
        # The squared weights are estimated from each bin's own clusters (10 to 200 here): with
        # weights as broad as an exponential's this puts chi2/bins ~10% high (1.12; 1.07 with ten
        # times the clusters), the price of an error bar that needs no spread.
        counting, scatter = self.chi2_per_bin(masses=True)
        self.assertTrue(self.MASSES_RANGE[0] < counting < self.MASSES_RANGE[1], counting)
        self.assertGreater(scatter, self.SCATTER_FLOOR)

    def test_realizations_holding_the_same_counts_still_have_an_error_bar(self):
        rng = numpy.random.default_rng(5)
        p = numpy.full(20, 1 / 20)
        one = self.hist(rng, p, masses=True, realizations=1)
        hist = {name: numpy.concatenate([value, value]) for name, value in one.items()}
        mean, error, z, use = sticky_pav.histogram_chi2(hist, p)
        self.assertTrue(use.all())
        self.assertTrue(numpy.all(error > 0) and numpy.all(numpy.isfinite(z)))
        numpy.testing.assert_allclose(error, numpy.sqrt(2 * one["sumw2"][0]) / 2)


# The exact theory's constants (exact_ballistic.py, docs/exact-theory.md). run_main() gives them to
# sticky_pav.main in place of their computation (8 s of quadrature per run), which the fit and the
# outputs do not depend on; the runs through the command line compute them.
CONSTANTS = dict(kappa=0.21285317851949462, nu=1.9156786097646632, kurtosis=3.0410086555363813)


def run_main(*arguments):
    """sticky_pav.main in this process with CONSTANTS: (exit status, stdout, stderr); a traceback
    would be an error of the test."""
    out, err = io.StringIO(), io.StringIO()
    with mock.patch.object(exact_ballistic, "compute_constants", return_value=CONSTANTS), \
            contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            status = sticky_pav.main([str(a) for a in arguments])
        except SystemExit as exit:
            status = exit.code
    return status, out.getvalue(), err.getvalue()


# A fit over three times as --compare prints it: r_inf, its jackknife sigma, a, its jackknife sigma,
# chi2, and the fit's own sigmas of r_inf and a.
FIT_LINE = (r"^r_inf = (\S+) \+- (\S+), a = (\S+) \+- (\S+) \(jackknife over realizations\), chi2/dof = (\S+)/1; "
            r"the fit's own widths, the times taken as independent: \+- (\S+), \+- (\S+)$")


def fit_lines(test, stdout):
    """The fit lines: {"T_ratio": what follows the colon, "n_ratio": ...}."""
    fits = dict(re.findall(r"^# fit (\w+) = r_inf \+ a t\^\(-1/3\): (.*)$", stdout, re.M))
    test.assertEqual(sorted(fits), ["T_ratio", "n_ratio"], stdout)
    return fits


class FiniteTimeFit(unittest.TestCase):
    """--compare's fit ratio(t) = r_inf + a t^(-1/3), weighted by the standard errors from the spread
    of the realizations."""

    def test_two_realizations_give_no_fit(self):
        # The probe's command. Seed 1: both realizations hold the same number of clusters at t = 400.
        result = pav("--N", 2000, "--realizations", 2, "--seed", 1, "--times", 100, 200, 400, "--compare")
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr[-3000:])
        self.assertNotIn("Traceback", result.stderr)
        for key, text in fit_lines(self, result.stdout).items():
            self.assertTrue(text.startswith("n/a (") and "5 or more, not 2" in text, text)
        rows = [line for line in result.stdout.splitlines() if re.match(r"\s+\d", line)]
        self.assertEqual(len(rows), 3, result.stdout)  # the table, all the same

    def test_a_time_without_spread(self):
        # At t = 0.001 no two neighbours have met: every realization holds N clusters.
        target = os.path.join(WORK, "no_spread.json")
        status, stdout, stderr = run_main("--N", 1000, "--realizations", 5, "--times", 0.001, 0.002, 0.004,
                                          "--compare", "--json", target)
        self.assertEqual(status, 0, stdout + stderr)
        fits = fit_lines(self, stdout)
        self.assertTrue(fits["n_ratio"].startswith("n/a (no error bar at t = 0.001, 0.002, 0.004: "), fits["n_ratio"])
        self.assertRegex(fits["T_ratio"], FIT_LINE)
        with open(target) as handle:
            written = json.load(handle)["fits"]
        self.assertIsNone(written["n_ratio"]["r_inf"])
        self.assertIn("no error bar", written["n_ratio"]["note"])
        self.assertTrue(math.isfinite(written["T_ratio"]["r_inf"]))

    def test_five_realizations_fit(self):
        status, stdout, stderr = run_main("--N", 2000, "--realizations", 5, "--times", 100, 200, 400, "--compare")
        self.assertEqual(status, 0, stdout + stderr)
        for key, text in fit_lines(self, stdout).items():
            numbers = re.fullmatch(FIT_LINE, text)
            self.assertIsNotNone(numbers, text)
            self.assertTrue(all(math.isfinite(float(x)) for x in numbers.groups()), text)

    def test_fit_finite_time(self):
        # Five realizations, each off the law 1 + 0.5 t^(-1/3) by its own constant at every time (as
        # correlated as values of one realization can be): the means lie on the law, r_inf and a are
        # exact; leaving a realization out moves every mean by the same amount, so the jackknife's
        # sigma of r_inf is the standard error of the offsets and that of a is 0.
        t = numpy.array([100.0, 200.0, 400.0, 800.0])
        offsets = numpy.array([-0.02, -0.01, 0.0, 0.01, 0.02])
        samples = 1.0 + 0.5 * t ** (-1.0 / 3.0) + offsets[:, None]
        rows = sticky_pav.compare_table(t, {"q": samples})
        fit = sticky_pav.fit_finite_time(rows, "q", samples)
        self.assertAlmostEqual(fit["r_inf"], 1.0, places=9)
        self.assertAlmostEqual(fit["a"], 0.5, places=8)
        self.assertEqual(fit["dof"], 2)
        self.assertAlmostEqual(fit["r_inf_err"], offsets.std(ddof=1) / math.sqrt(len(offsets)), places=12)
        self.assertAlmostEqual(fit["a_err"], 0.0, places=10)
        self.assertGreater(fit["r_inf_fit_err"], 0.0)
        few = sticky_pav.fit_finite_time(sticky_pav.compare_table(t, {"q": samples[:4]}), "q", samples[:4])
        self.assertIsNone(few["r_inf"])
        self.assertIn("5 or more, not 4", few["note"])
        rows[1]["q_err"] = 0.0
        flat = sticky_pav.fit_finite_time(rows, "q", samples)
        self.assertIsNone(flat["chi2"])
        self.assertIn("t = 200", flat["note"])


class JackknifeErrors(unittest.TestCase):
    """--compare's sigma of r_inf against the spread of r_inf over independent ensembles (seeds fixed):
    N = 2000, R = 10, 9 times from 10 to 400. The fit's own sigma, which takes the times as
    independent, is about half that spread (0.54 for T, 0.62 for n with these seeds; 0.48 to 0.62
    over five such sets of seeds): it was the +- printed. The jackknife over realizations gives 0.94
    and 1.02 (0.82 to 1.05)."""

    ENSEMBLES, N, REALIZATIONS, FIRST_SEED = 100, 2000, 10, 1
    TIMES = numpy.geomspace(10.0, 400.0, 9)
    # The spread of 100 values is itself known to ~7% (1/sqrt(2 x 99)): the fit's sigma must stay
    # below 0.75 of it (measured 0.48 to 0.62), the jackknife's within 0.75 to 1.3 (0.82 to 1.05).
    FIT_TO_SPREAD_CEILING = 0.75
    JACKKNIFE_TO_SPREAD_RANGE = (0.75, 1.3)

    def test_the_jackknife_follows_the_spread_over_ensembles(self):
        fits = {"T_ratio": [], "n_ratio": []}
        for ensemble in range(self.ENSEMBLES):
            ens = sticky_pav.run_ensemble(self.N, self.REALIZATIONS, self.FIRST_SEED + ensemble * self.REALIZATIONS,
                                          self.TIMES, verbose=False)
            ratios = sticky_pav.per_realization_ratios(ens, CONSTANTS["kappa"], CONSTANTS["nu"])
            rows = sticky_pav.compare_table(ens["times"], ratios)
            for key, found in fits.items():
                found.append(sticky_pav.fit_finite_time(rows, key, ratios[key]))
        for key, found in fits.items():
            with self.subTest(key):
                spread = numpy.std([fit["r_inf"] for fit in found], ddof=1)

                def rms(name):
                    return math.sqrt(numpy.mean([fit[name] ** 2 for fit in found]))
                self.assertLess(rms("r_inf_fit_err") / spread, self.FIT_TO_SPREAD_CEILING)
                low, high = self.JACKKNIFE_TO_SPREAD_RANGE
                self.assertTrue(low < rms("r_inf_err") / spread < high, (rms("r_inf_err"), spread))


class Outputs(unittest.TestCase):
    """An output that cannot be written is refused in one line naming the option, the path and the
    cause: before the work where it can be told (no realization is run: the error is the one line on
    stderr), else when written."""

    ENSEMBLE = ("--N", 2000, "--realizations", 2, "--seed", 2, "--times", 100, 200, 400, "--compare")

    @classmethod
    def setUpClass(cls):
        cls.dir = os.path.join(WORK, "outputs")
        shutil.rmtree(cls.dir, ignore_errors=True)
        os.makedirs(cls.dir)
        cls.plain = os.path.join(cls.dir, "plain.txt")
        with open(cls.plain, "w") as handle:
            handle.write("a file\n")
        cls.init = os.path.join(cls.dir, "init.txt")
        with open(cls.init, "w") as handle:
            handle.write("# L = 4\n0 0.5\n1 -0.5\n2 0.1\n3 0.2\n")

    def test_before_the_work(self):
        missing = os.path.join(self.dir, "no_such_dir")
        for arguments, words in [
                (("--json", os.path.join(missing, "c.json")), ("--json", "no_such_dir", "does not exist")),
                (("--hist-dir", os.path.join(self.plain, "hist")), ("--hist-dir", "plain.txt", "is not a directory")),
                (("--hist-dir", self.plain), ("--hist-dir", "plain.txt", "not a directory")),
                (("--json", self.dir), ("--json", "it is a directory"))]:
            with self.subTest(arguments=arguments):
                sc.one_line_error(self, pav(*self.ENSEMBLE, *arguments), NAME, *words)
        clusters = os.path.join(missing, "c.txt")
        sc.one_line_error(self, pav("--init", self.init, "--times", 1, "--clusters-out", clusters), NAME,
                          "--clusters-out", "no_such_dir", "does not exist")
        self.assertFalse(os.path.exists(missing))
        with open(self.plain) as handle:
            self.assertEqual(handle.read(), "a file\n")

    def test_read_only_directory(self):
        if os.geteuid() == 0:
            self.skipTest("run as root, who may write in a read-only directory")
        locked = os.path.join(self.dir, "locked")
        os.makedirs(locked, exist_ok=True)
        os.chmod(locked, 0o555)
        try:
            sc.one_line_error(self, pav(*self.ENSEMBLE, "--json", os.path.join(locked, "c.json")), NAME, "--json",
                              "Permission denied")
        finally:
            os.chmod(locked, 0o755)

    def test_full_disk(self):
        if not os.path.exists("/dev/full"):
            self.skipTest("no /dev/full")
        sc.one_line_error(self, pav("--init", self.init, "--times", 1, "--clusters-out", "/dev/full"), NAME,
                          "--clusters-out", "/dev/full", "No space left on device")
        status, stdout, stderr = run_main(*self.ENSEMBLE, "--json", "/dev/full")
        self.assertEqual(status, 2, stderr)
        # In this process the program is named after the test (sys.argv[0]).
        self.assertTrue(stderr.strip().splitlines()[-1].endswith(
            ": error: cannot write --json '/dev/full': No space left on device"), stderr)
        self.assertNotIn("Traceback", stderr)


# A ring of L = 5 holding 10 particles at x = 0..9: half of them outside [0, L).
OUTSIDE_RING_LENGTH = 5
OUTSIDE_PARTICLES = 10


def particles(count):
    """--init text of `count` unit masses at x = 0, 1, ..., velocities of alternating sign."""
    return "".join("%d %g\n" % (i, (-1) ** i * 0.1 * i) for i in range(count))


class InitFile(unittest.TestCase):
    """--init reads text columns 'x v [m]': other files, and particles off the ring, in one line."""

    @classmethod
    def setUpClass(cls):
        cls.dir = os.path.join(WORK, "init_file")
        shutil.rmtree(cls.dir, ignore_errors=True)
        os.makedirs(cls.dir)

    def write(self, name, text):
        target = os.path.join(self.dir, name)
        with open(target, "w") as handle:
            handle.write(text)
        return target

    def test_an_hdf5_init_file_is_the_same_start_as_its_text(self):
        try:
            import h5py  # noqa: F401
        except ImportError as error:  # h5py missing: this test alone cannot make its file
            self.skipTest("needs h5py to write an HDF5 init file (%s)" % error)
        import shockgas  # from PYTHONPATH (ctest's): missing, the test fails rather than skips
        x, v, m = [0.0, 1.5, 3.0, 4.2], [0.5, -0.2, 0.3, -0.6], [1.0, 2.0, 1.0, 0.5]
        start = os.path.join(self.dir, "start.h5")
        shockgas.write_initial_condition(start, x, v, mass=m, ring_length=5.0, overwrite=True)
        text = self.write("start.txt", "# L = 5\n" + "".join("%r %r %r\n" % row for row in zip(x, v, m)))
        from_hdf5 = pav("--init", start, "--times", 1, 3)
        from_text = pav("--init", text, "--times", 1, 3)
        self.assertEqual(from_hdf5.returncode, 0, from_hdf5.stderr)
        self.assertNotIn("codec", from_hdf5.stderr)
        self.assertEqual(from_hdf5.stdout, from_text.stdout)
        self.assertGreater(len(from_hdf5.stdout.splitlines()), 2)
        # Its ring length is the file's: another --L is refused, naming both.
        sc.one_line_error(self, pav("--init", start, "--L", 6, "--times", 1), NAME, "--L 6.0",
                          "ring_length is 5.0")

    def test_a_malformed_hdf5_start_is_one_line(self):
        try:
            import h5py
        except ImportError as error:  # pragma: no cover - h5py missing: this test alone cannot make its files
            self.skipTest("needs h5py to write an HDF5 init file (%s)" % error)
        for name, words in sc.MALFORMED_STARTS:
            with self.subTest(start=name):
                start = os.path.join(self.dir, name + ".h5")
                with h5py.File(start, "w") as handle:
                    sc.write_malformed_start(handle, name)
                result = pav("--init", start, "--times", 1)
                sc.one_line_error(self, result, NAME, name + ".h5", *words)
                self.assertEqual(result.stdout, "")

    def test_positions_outside_the_ring(self):
        init = self.write("outside.txt", particles(OUTSIDE_PARTICLES))
        result = pav("--init", init, "--L", OUTSIDE_RING_LENGTH, "--times", 1)
        sc.one_line_error(self, result, NAME, "outside.txt", "x = 5.0", "outside the ring [0, L = 5.0)")
        self.assertEqual(result.stdout, "")
        # The ring's length taken from the file ('# L =' line), too small for its positions.
        init = self.write("outside_header.txt", "# L = 2\n0 0.5\n1 -0.5\n2 0.1\n")
        sc.one_line_error(self, pav("--init", init, "--times", 1), NAME, "x = 2.0", "[0, L = 2.0)")
        # Inside, the same particles give every particle a cluster: masses add up to N.
        init = self.write("inside.txt", particles(OUTSIDE_PARTICLES))
        result = pav("--init", init, "--L", 2 * OUTSIDE_PARTICLES, "--times", 1)
        self.assertEqual(result.returncode, 0, result.stderr)
        masses = [float(line.split()[1]) for line in result.stdout.splitlines() if not line.startswith("#")]
        self.assertEqual(sum(masses), OUTSIDE_PARTICLES)

    def test_no_particles_is_the_error_line_alone(self):
        for name, text in (("empty.txt", ""), ("comments.txt", "# L = 4\n# nothing else\n")):
            with self.subTest(file=name):
                result = pav("--init", self.write(name, text), "--times", 1)
                sc.one_line_error(self, result, NAME, name, "no particles")
                self.assertNotIn("Warning", result.stderr)


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
