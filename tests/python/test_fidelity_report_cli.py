#!/usr/bin/python3
"""tools/fidelity_report.py refuses what would print empty tables (ctest python.fidelity_report_inputs,
label python; < 1 s).

    test_fidelity_report_cli.py SIM WORK_DIR

On a miniature quick build (paper_targets/quick/fig1/r0.h5, one tiny run) the report lists it
(exit 0). Refused with exit status 2 and one line (they printed empty tables and exit 0, or a
traceback): asking that quick build for paper (it has no paper_targets/paper/; the check was on
paper_targets/ only), also with --progress; a build whose paper_targets/quick/ holds no results;
--check-readme with no file after it (IndexError) or with a file that does not exist
(FileNotFoundError); a build directory that does not exist; an unknown fidelity (exit 1 before).
"""
import os
import shutil
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
import script_checks as sc  # noqa: E402

sc.require("h5py", "numpy")

SIM, WORK = sc.arguments(2)
TOOL = sc.script("tools", "fidelity_report.py")
NAME = "fidelity_report.py"


def report(*arguments):
    return sc.run([sc.PYTHON, TOOL, *arguments], cwd=WORK)


class Inputs(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        shutil.rmtree(WORK, ignore_errors=True)
        cls.build = os.path.join(WORK, "build")
        figure = os.path.join(cls.build, "paper_targets", "quick", "fig1")
        os.makedirs(figure)
        result = sc.run([SIM, "-N", 1000, "-r", 0, "-t", 100, "-R", 2, "-j", 1, "-q", "-o", "r0.h5"], cwd=figure)
        assert result.returncode == 0, result.stderr
        cls.empty = os.path.join(WORK, "configured")
        os.makedirs(os.path.join(cls.empty, "paper_targets", "quick", "fig1"))

    def test_the_quick_build_is_reported(self):
        result = report(self.build, "quick")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertRegex(result.stdout, r"\| fig1 \| 1 \| 1e3 \| 2 \|")

    def test_another_fidelity_than_the_build_has(self):
        sc.one_line_error(self, report(self.build, "paper"), NAME, "no paper_targets/paper/")
        sc.one_line_error(self, report(self.build, "paper", "--progress"), NAME, "no paper_targets/paper/")
        sc.one_line_error(self, report(self.build, "slow"), NAME, "quick or paper")

    def test_no_results_yet(self):
        sc.one_line_error(self, report(self.empty, "quick"), NAME, "no results", "build the figures first")
        sc.one_line_error(self, report(self.empty, "quick", "--readme"), NAME, "no results")

    def test_check_readme_needs_a_file(self):
        sc.one_line_error(self, report(self.build, "quick", "--check-readme"), NAME, "--check-readme needs")
        sc.one_line_error(self, report(self.build, "quick", "--check-readme", os.path.join(WORK, "NO_README.md")),
                          NAME, "NO_README.md", "no such file")

    def test_no_build_directory(self):
        sc.one_line_error(self, report(os.path.join(WORK, "no-build"), "quick"), NAME, "no such directory")


if __name__ == "__main__":
    unittest.main(verbosity=2)
