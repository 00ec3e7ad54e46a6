#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""tools/compare_engine_ensembles.py refuses what it cannot compare, and a NaN statistic fails
(ctest python.compare_engine_ensembles, label python; about 10 s of CPU).

    test_compare_engine_ensembles_cli.py SIM WORK_DIR

The script must not pass (exit 0) two one-realization files (standard error NaN, and abs(nan) > 3
is False), compare A's t = 100 with B's last sample when B's grid is another (IndexError the other
way round), or skip a file without histograms in silence (as pairing them with zip would). So:
  * the same run made by the event and the pass-through engine (3 realizations, histograms at
    t = 10 and 50) is compared and passes (exit 0): the two engines agree here sample for sample;
  * one realization in either file, another restitution, another t_max (either order), another
    sample grid with the same attributes, histograms missing from one file: exit 2, one line;
  * another seed is what is compared: not refused;
  * runs whose every realization collapsed (delta = 0) leave samples without any standard error:
    a NaN statistic, which fails (exit 1), not passes;
  * 4 realizations against 20 of the same law pass the permutation test where the chi-square law
    alone would reject them;
  * --mechanisms compares elastic with sticky sub-threshold runs (refused without it), fails where
    the mechanism changes the law (delta = 0.3), and still refuses another restitution.
"""
import os
import re
import shutil
import unittest

import script_checks as sc

# h5py only to alter copies of runs (a time grid, a histogram group) on purpose
h5py, *_ = sc.require("h5py", "numpy", "scipy")

SIM, WORK = sc.arguments(2)
os.makedirs(WORK, exist_ok=True)
TOOL = sc.script("tools", "compare_engine_ensembles.py")
NAME = "compare_engine_ensembles.py"
# The runs: N = 1000, r = 0.9, delta = 0.01 to t = 100 (a few ms each).
COMMON = ["-N", 1000, "-r", 0.9, "-d", 0.01, "-j", 1, "-q"]


def path(name):
    return os.path.join(WORK, name)


def simulate(name, *options):
    if os.path.exists(path(name)):
        os.remove(path(name))
    result = sc.run([SIM, *options, "-o", path(name)], cwd=WORK)
    assert result.returncode == 0, result.stderr


def compare(a, b):
    return sc.run([sc.PYTHON, TOOL, path(a), path(b)], cwd=WORK)


class Refusals(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        histograms = ["--histogram-times", "10,50"]
        simulate("event.h5", *COMMON, "-t", 100, "-R", 3, "-s", 1, *histograms)
        simulate("passthrough.h5", *COMMON, "-t", 100, "-R", 3, "-s", 1, "--engine", "passthrough", *histograms)
        simulate("passthrough_seed2.h5", *COMMON, "-t", 100, "-R", 3, "-s", 2, "--engine", "passthrough", *histograms)
        simulate("one_event.h5", *COMMON, "-t", 100, "-R", 1, "-s", 1, *histograms)
        simulate("one_passthrough.h5", *COMMON, "-t", 100, "-R", 1, "-s", 1, "--engine", "passthrough", *histograms)
        simulate("longer.h5", *COMMON, "-t", 200, "-R", 3, "-s", 1, *histograms)
        simulate("r05.h5", "-N", 1000, "-r", 0.5, "-d", 0.01, "-j", 1, "-q", "-t", 100, "-R", 3, *histograms)

    def altered(self, name, change):
        """A copy of event.h5 with one thing changed, its attributes left as they are."""
        shutil.copyfile(path("event.h5"), path(name))
        with h5py.File(path(name), "r+") as handle:
            change(handle)
        return name

    def test_same_run_two_engines_passes(self):
        result = compare("event.h5", "passthrough.h5")
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertIn("T(t): 23 samples", result.stdout)  # t = 0 and 10 per decade to 100: 22, and t_max
        self.assertEqual(result.stdout.count("histogram t = "), 2)

    def test_one_realization_is_refused(self):
        for a, b in (("one_event.h5", "one_passthrough.h5"), ("event.h5", "one_passthrough.h5")):
            sc.one_line_error(self, compare(a, b), NAME, "1 realization", "at least 2")

    def test_other_physics_is_refused(self):
        sc.one_line_error(self, compare("event.h5", "r05.h5"), NAME, "restitution 0.9 vs 0.5")

    def test_other_length_is_refused_in_either_order(self):
        # Once: exit 0 with A's t = 100 compared against B's last column "at t = 100", or IndexError.
        for a, b in (("event.h5", "longer.h5"), ("longer.h5", "event.h5")):
            sc.one_line_error(self, compare(a, b), NAME, "t_max")

    def test_other_sample_times_are_refused(self):
        def shift(handle):
            handle["timeseries/time"][5] *= 1.01
        sc.one_line_error(self, compare("event.h5", self.altered("other_grid.h5", shift)), NAME, "sample times")

    def test_missing_histograms_are_refused(self):
        def drop(handle):
            del handle["histograms"]
        copy = self.altered("no_histograms.h5", drop)
        for a, b in (("event.h5", copy), (copy, "event.h5")):
            sc.one_line_error(self, compare(a, b), NAME, "histogram times")

    def test_another_seed_is_compared(self):
        result = compare("event.h5", "passthrough_seed2.h5")
        self.assertIn(result.returncode, (0, 1), result.stderr)
        self.assertIn("T(t): 23 samples", result.stdout)

    def test_bad_paths(self):
        sc.one_line_error(self, compare("event.h5", "no_such.h5"), NAME, "no_such.h5", "no such file")
        sc.one_line_error(self, sc.run([sc.PYTHON, TOOL, path("event.h5")]), NAME, "required", "B.h5")


class FewRealizations(unittest.TestCase):
    def test_the_permutation_test_holds_where_the_chi_square_law_does_not(self):
        # The same law twice: the sticky gas (r = 0, N = 5000), 4 realizations (seed 5) against 20
        # (seed 2). Each bin's error comes from 4 realizations' spread, so the z-scores are
        # Student-t-like and their sum far above its chi-square law: that law's p-value is below
        # 1e-3 at t = 300 (chi2 = 109 for 61 bins). The permutation test, which
        # decides, passes at both times.
        simulate("few.h5", "-N", 5000, "-r", 0, "-t", 1000, "-R", 4, "-s", 5, "-j", 1, "-q",
                 "--histogram-times", "300,1000")
        simulate("many.h5", "-N", 5000, "-r", 0, "-t", 1000, "-R", 20, "-s", 2, "-j", 1, "-q",
                 "--histogram-times", "300,1000")
        result = compare("few.h5", "many.h5")
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        law = [float(p) for p in re.findall(r"chi-square law ([0-9.]+)", result.stdout)]
        self.assertEqual(len(law), 2, result.stdout)
        self.assertLess(law[0], 1e-3, result.stdout)


class Mechanisms(unittest.TestCase):
    """--mechanisms: elastic against sticky sub-threshold collisions, the paper's two, compared."""

    @classmethod
    def setUpClass(cls):
        # delta = 0.3: most collisions are below it, so the mechanism decides the dynamics and by
        # t = 50 sticky merging has narrowed the velocity law far more than elastic bouncing.
        wide = ["-N", 1000, "-r", 0.9, "-d", 0.3, "-t", 50, "-R", 6, "-s", 1, "-j", 1, "-q",
                "--histogram-times", "10,50"]
        simulate("wide_elastic.h5", *wide)
        simulate("wide_sticky.h5", *wide, "--subthreshold", "sticky")
        simulate("wide_sticky_r05.h5", *wide[:2], "-r", 0.5, *wide[4:], "--subthreshold", "sticky")

    def mechanisms(self, a, b):
        return sc.run([sc.PYTHON, TOOL, "--mechanisms", path(a), path(b)], cwd=WORK)

    def test_without_the_option_other_mechanisms_are_refused(self):
        sc.one_line_error(self, compare("wide_elastic.h5", "wide_sticky.h5"), NAME, "subthreshold")

    def test_a_law_the_mechanism_changes_fails(self):
        result = self.mechanisms("wide_elastic.h5", "wide_sticky.h5")
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertIn("sub-threshold mechanisms: elastic (A) and sticky (B)", result.stdout)
        self.assertRegex(result.stdout, r"histogram t = 50: .* FAIL")
        # The collision counts differ by what each mechanism counts: reported, not compared.
        self.assertIn("not compared", result.stdout)

    def test_other_physics_is_still_refused(self):
        sc.one_line_error(self, self.mechanisms("wide_elastic.h5", "wide_sticky_r05.h5"), NAME, "restitution")


class NotANumber(unittest.TestCase):
    def test_samples_without_a_standard_error_fail(self):
        # delta = 0, r = 0.5, N = 200: every realization collapses by t ~ 15 (seeds 1 and 2, both
        # realizations), so T is NaN at every later sample in both files and the standard errors
        # there are NaN: each such sample fails, as does the NaN collision count at the end.
        simulate("collapse1.h5", "-N", 200, "-r", 0.5, "-d", 0, "-t", 100, "-R", 2, "-s", 1, "-j", 1, "-q")
        simulate("collapse2.h5", "-N", 200, "-r", 0.5, "-d", 0, "-t", 100, "-R", 2, "-s", 2, "-j", 1, "-q")
        result = compare("collapse1.h5", "collapse2.h5")
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertIn("FAIL: no standard error at", result.stdout)
        self.assertRegex(result.stdout, r"collisions per particle .* z = nan FAIL")


if __name__ == "__main__":
    unittest.main(verbosity=2)
