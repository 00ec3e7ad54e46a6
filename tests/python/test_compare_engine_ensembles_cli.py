#!/usr/bin/python3
"""tools/compare_engine_ensembles.py refuses what it cannot compare, and a NaN statistic fails
(ctest python.compare_engine_ensembles, label python; about 1 s of CPU).

    test_compare_engine_ensembles_cli.py SIM WORK_DIR

Before this test the script passed (exit 0) two one-realization files (standard error NaN, and
abs(nan) > 3 is False), compared A's t = 100 with B's last sample when B's grid was another
(IndexError the other way round), and paired histograms with zip, so a file without them was
skipped in silence. Now:
  * the same run made by the event and the pass-through engine (3 realizations, histograms at
    t = 10 and 50) is compared and passes (exit 0): the two engines agree here sample for sample;
  * one realization in either file, another restitution, another t_max (either order), another
    sample grid with the same attributes, histograms missing from one file: exit 2, one line;
  * another seed is what is compared: not refused;
  * runs whose every realization collapsed (delta = 0) leave samples without any standard error:
    a NaN statistic, which fails (exit 1), not passes.
"""
import os
import shutil
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
import script_checks as sc  # noqa: E402

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
