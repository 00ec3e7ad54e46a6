#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""tools/fidelity_report.py refuses what would print empty tables (ctest python.fidelity_report_inputs,
label python; < 1 s).

    test_fidelity_report_cli.py SIM WORK_DIR

On a miniature quick build (paper_targets/quick/fig1/r0.h5, one tiny run) the report lists it
(exit 0). Refused with exit status 2 and one line (not empty tables and exit 0, nor a
traceback): asking that quick build for paper (it has no paper_targets/paper/; the check was on
paper_targets/ only), also with --progress; a build whose paper_targets/quick/ holds no results;
--check-readme with no file after it (IndexError) or with a file that does not exist
(FileNotFoundError); a build directory that does not exist; an unknown fidelity (not exit 1).
Fig. 4's tail rows (a scaling.h5 written here with each case shockgas-analyze stores) print n/a with
the reason, or the fit's Δχ² = 1 width where only the jackknife failed, and never "nan" (as in
"γ = 0.75 ± nan" for a quick build's short runs). The reason is the one the analysis stored
(tail_gamma_note, tail_gamma_sigma_note, tail_error), not the report's own words; files without a
stored reason get those: "too few tail bins" for one realization and "a replica at the search bound"
for two.
"""
import math
import os
import shutil
import unittest

import script_checks as sc

h5py, _ = sc.require("h5py", "numpy")
import shockgas.schema  # noqa: E402

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
        cls.write_tail_cases(os.path.join(cls.build, "paper_targets", "quick", "fig4"))
        cls.empty = os.path.join(WORK, "configured")
        os.makedirs(os.path.join(cls.empty, "paper_targets", "quick", "fig1"))

    @staticmethod
    def write_tail_cases(directory):
        """scaling.h5 as shockgas-analyze scaling writes it, one histogram per way the tail fit ends:
        a fit with its jackknife; a jackknife replica at the search bound (σ NaN); γ itself at the
        bound (NaN); too few tail bins (tail_error, no tail_gamma); two realizations (σ NaN); one
        realization (tail_error, and the kurtosis's σ NaN). Cases 1 and 2 lack the notes, as files
        written before the notes."""
        os.makedirs(directory)
        nan = math.nan
        cases = [{"tail_gamma": 3.04, "tail_gamma_sigma": 1.24, "tail_gamma_fit_sigma": 1.5},
                 {"tail_gamma": 0.75, "tail_gamma_sigma": nan, "tail_gamma_fit_sigma": 0.73},
                 {"tail_gamma": nan, "tail_gamma_sigma": nan, "tail_gamma_fit_sigma": nan},
                 {"tail_error": "only 3 tail bins have a relative error below the limit"},
                 {"tail_gamma": 2.9, "tail_gamma_sigma": nan, "tail_gamma_fit_sigma": 0.4,
                  "tail_gamma_sigma_note": "two realizations: each jackknife replica keeps one"},
                 {"tail_error": "the tail fit weighs bins by realization scatter: needs R >= 2",
                  "kurtosis_sigma": nan, "kurtosis_sigma_note": "one realization: the jackknife has nothing to leave out"},
                 {"tail_gamma": nan, "tail_gamma_sigma": nan, "tail_gamma_fit_sigma": nan,
                  "tail_gamma_note": "at the search bound 8 of [0.5, 8]: the minimum lies beyond the range"}]
        with h5py.File(os.path.join(directory, "scaling.h5"), "w") as f:
            f.attrs["program"] = "shockgas-analyze scaling"
            f.attrs["schema_version"] = max(shockgas.schema.SCHEMA_VERSIONS)
            f.create_group("collapse").attrs.update({"beta": 0.335, "beta_sigma": 0.006})
            for i, case in enumerate(cases):
                group = f.create_group(f"histogram{i}")
                group.attrs.update({"label": f"case{i}", "kurtosis": 3.0, "kurtosis_sigma": 0.1, **case})

    def test_tail_rows_say_why_a_number_is_missing(self):
        result = report(self.build, "quick")
        self.assertEqual(result.returncode, 0, result.stderr)
        rows = {line.split(":")[0].split()[-1]: line for line in result.stdout.splitlines()
                if line.startswith("| Fig. 4 case")}
        self.assertEqual(len(rows), 7, result.stdout)
        self.assertIn("γ = 3.04 ± 1.24 |", rows["case0"])
        self.assertIn("γ = 0.75 ± 0.73 (Δχ² = 1; jackknife n/a: a replica at the search bound)", rows["case1"])
        self.assertIn("γ n/a (at the search bound)", rows["case2"])
        self.assertIn("γ n/a (only 3 tail bins have a relative error below the limit)", rows["case3"])
        self.assertIn("γ = 2.90 ± 0.40 (Δχ² = 1; jackknife n/a: two realizations: each jackknife replica keeps "
                      "one)", rows["case4"])
        self.assertIn("3.000 ± n/a (one realization: the jackknife has nothing to leave out); γ n/a (the tail fit "
                      "weighs bins by realization scatter: needs R >= 2)", rows["case5"])
        self.assertIn("γ n/a (at the search bound 8 of [0.5, 8]: the minimum lies beyond the range)", rows["case6"])
        self.assertNotIn("nan", result.stdout.lower())

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
