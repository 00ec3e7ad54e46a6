#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""python/refit_check.py finds the run its results were computed from, or refuses; one realization;
bad inputs (ctest python.refit_check_inputs, label python; about 1 s of CPU).

    test_refit_check_cli.py SIM ANALYZE WORK_DIR

The results file stores input_path as it was given to shockgas-analyze ("run.h5"). Were the script to
look in the current directory first, then run from a directory holding another run.h5 it would refit
that one and report a C++-versus-scipy mismatch of its own making. Here:
  * a/run.h5 (seed 3) and its decay fit a/decay.h5, made in a/; b/run.h5 another run (seed 9).
    From b/, refit_check.py ../a/decay.h5 refits a/run.h5 and agrees (exit 0);
  * a copy of the results in b/ (its input, a/run.h5, is not beside it): b/run.h5 is found and
    refused because its seed differs from the recorded one; --run naming the wrong run too: exit 2;
  * one realization: the C++ gives exponent_sigma NaN ("+- n/a"); the refit compares the exponent
    and chi2/dof and reports sigma as n/a on both sides (it died with "array must not contain infs
    or NaNs"); two the same, the note saying "(2 realizations: ...", not "(2 realization: ...";
  * a run file given as results, a missing file, results of another subcommand: exit 2, one line.
"""
import os
import shutil
import unittest

import script_checks as sc

sc.require("h5py", "numpy", "scipy")

SIM, ANALYZE, WORK = sc.arguments(3)
TOOL = sc.script("python", "refit_check.py")
NAME = "refit_check.py"
# The agreement refit_check.py itself defaults to: the C++ and scipy fits of the same numbers agree
# to rounding and the minimisers' tolerances (measured 3e-8 relative at worst on the sigma).
TOLERANCE = "1e-6"


def make(directory, name, *options):
    os.makedirs(directory, exist_ok=True)
    target = os.path.join(directory, name)
    if os.path.exists(target):
        os.remove(target)
    result = sc.run([SIM, "-N", 2000, "-r", 0, "-t", 1000, "-j", 1, "-q", *options, "-o", name], cwd=directory)
    assert result.returncode == 0, result.stderr


def analyze(directory, run, results, subcommand="decay"):
    result = sc.run([ANALYZE, subcommand, run, "-o", results], cwd=directory)  # input_path as given: "run.h5"
    assert result.returncode == 0, result.stderr


def refit(*arguments, cwd):
    return sc.run([sc.PYTHON, TOOL, *arguments, "--tolerance", TOLERANCE], cwd=cwd)


class FindsTheAnalysedRun(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.a, cls.b = os.path.join(WORK, "a"), os.path.join(WORK, "b")
        make(cls.a, "run.h5", "-R", 4, "-s", 3)
        analyze(cls.a, "run.h5", "decay.h5")
        make(cls.b, "run.h5", "-R", 4, "-s", 9)

    def test_from_another_directory_refits_the_run_beside_the_results(self):
        result = refit("../a/decay.h5", cwd=self.b)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertIn("seed 3", result.stdout)
        self.assertIn(os.path.join(self.a, "run.h5"), result.stdout)
        self.assertNotIn("FAIL", result.stdout)

    def test_a_run_that_is_not_the_analysed_one_is_refused(self):
        shutil.copyfile(os.path.join(self.a, "decay.h5"), os.path.join(self.b, "moved.h5"))
        sc.one_line_error(self, refit("moved.h5", cwd=self.b), NAME, "seed is 9", "was 3")
        sc.one_line_error(self, refit(os.path.join(self.a, "decay.h5"), "--run", os.path.join(self.b, "run.h5"),
                                      cwd=WORK), NAME, "seed is 9")
        # The right one named with --run is accepted.
        result = refit("moved.h5", "--run", os.path.join(self.a, "run.h5"), cwd=self.b)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)

    def test_bad_inputs(self):
        sc.one_line_error(self, refit("run.h5", cwd=self.b), NAME, "not a results file")
        sc.one_line_error(self, refit("no_such.h5", cwd=self.b), NAME, "no_such.h5", "no such file")
        directory = os.path.join(WORK, "shocks")
        os.makedirs(directory, exist_ok=True)
        result = sc.run([SIM, "-N", 2000, "-r", 0.9, "-t", 100, "--snapshot-times", 100, "-j", 1, "-q",
                         "-o", "profile.h5"], cwd=directory)
        self.assertEqual(result.returncode, 0, result.stderr)
        analyze(directory, "profile.h5", "shocks.h5", subcommand="shocks")
        sc.one_line_error(self, refit("shocks.h5", cwd=directory), NAME, "no /decay section")


class TooFewToWeigh(unittest.TestCase):
    """One or two realizations: the exponent is the unweighted fit on both sides, sigma and chi2 n/a."""

    def expect_unweighted_on_both_sides(self, realizations):
        directory = os.path.join(WORK, "R%d" % realizations)
        make(directory, "run.h5", "-R", realizations, "-s", 9)
        analyze(directory, "run.h5", "decay.h5")
        result = refit("decay.h5", cwd=directory)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertRegex(result.stdout, r"exponent +C\+\+ [0-9.]+ +scipy [0-9.]+ +relative difference \S+ ok")
        self.assertRegex(result.stdout, r"exponent_sigma +C\+\+ n/a +scipy n/a .* ok")
        self.assertRegex(result.stdout, r"chi2_per_dof +C\+\+ n/a +scipy n/a .* ok")
        # The n/a notes count the realizations in words that agree with the number (not "(2 realization:"
        # for two).
        counted = "%d realization%s:" % (realizations, "" if realizations == 1 else "s")
        for key in ("exponent_sigma", "chi2_per_dof"):
            line = next(line for line in result.stdout.splitlines() if line.startswith(key))
            self.assertIn("n/a on both sides (%s" % counted, line)

    def test_one_realization(self):
        self.expect_unweighted_on_both_sides(1)

    # Two: the C++ fits unweighted with sigma and chi2 n/a, and so must the refit (weighed by the
    # two-value standard error, it would fail on every R = 2 result).
    def test_two_realizations(self):
        self.expect_unweighted_on_both_sides(2)


if __name__ == "__main__":
    unittest.main(verbosity=2)
