#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Every Python command-line script refuses a bad command line in one line (ctest
python.script_refusals, label python; about 4 s of CPU, most of it importing numpy and scipy).

    test_script_refusals_cli.py WORK_DIR

The house rule (tests/python/script_checks.py): a user's mistake is one line "<script>: error: ..."
on stderr and exit status 2, without argparse's usage block (up to eight lines) above that line: the
scripts parse with shockgas.cli.ArgumentParser (python/shockgas/cli.py), the one place that says how. Checked for each script: an unknown option, named in the line; for
the argparse ones also a missing argument, a bad number and a bad choice where they have them, and
--help, which still prints argparse's help on stdout with exit status 0. fidelity_report.py, which
parses its words by hand, prints its help in argparse's form wherever -h or --help stands (not an
unknown option). Nothing is run: every command is refused, or answered, before
any file is read.

exact_ballistic.py --D, the momentum variance per unit length of the initial velocities: 0 ended in a
ZeroDivisionError traceback, -1 in a TypeError about complex numbers after writing phi.dat, NaN and
infinity wrote constants.gp with exact_kappa = nan (or inf) and exit 0. Each is now one line naming
--D, exit 2, and --out-dir is not made.
"""
import os
import unittest

import script_checks as sc

sc.require("h5py", "numpy", "scipy")

WORK = sc.arguments(1)
UNKNOWN = "--no-such-option"

# (folder, script, arguments before the unknown option: the required ones, so that the refusal is
# about the option and not about what is missing; nothing is read).
SCRIPTS = [
    ("python", "refit_check.py", ["decay.h5"]),
    ("python", "clusters_check.py", ["clusters.h5"]),
    ("python", "tails_check.py", ["late.h5"]),
    ("python", "reference_gas.py", ["start.h5"]),
    ("python", "sticky_pav.py", []),
    ("python", "exact_ballistic.py", ["--out-dir", "theory"]),
    (os.path.join("tests", "python"), "test_schema.py", ["run.h5"]),
    ("tools", "compare_engine_ensembles.py", ["a.h5", "b.h5"]),
    ("tools", "fidelity_report.py", []),
    ("tools", "reproduce-check", ["archive.tar.gz"]),
]
# exact_ballistic.py --D values that are no variance (given as --D=VALUE, as argparse reads "-inf"
# as an option otherwise).
BAD_D = ["0", "-1", "nan", "inf", "-inf"]
# fidelity_report.py parses its few words itself (its refusals were one line already); its --help, which
# it refused as an unknown option, has argparse's form.
ARGPARSE_SCRIPTS = [(folder, name) for folder, name, _ in SCRIPTS if name != "fidelity_report.py"]


def run(folder, name, *arguments):
    return sc.run([sc.PYTHON, sc.script(folder, name), *arguments], cwd=WORK)


class UnknownOption(unittest.TestCase):
    def test_every_script_refuses_in_one_line(self):
        for folder, name, arguments in SCRIPTS:
            with self.subTest(script=name):
                sc.one_line_error(self, run(folder, name, *arguments, UNKNOWN), name, UNKNOWN)

    def test_a_subcommand_too(self):
        result = run("tools", "reproduce-check", "pack", "--build-dir", "b", "--source-dir", "s", "--fidelity", "quick",
                     "--figures", "fig1", UNKNOWN)
        sc.one_line_error(self, result, "reproduce-check pack", UNKNOWN)


class OtherRefusals(unittest.TestCase):
    def test_missing_argument(self):
        sc.one_line_error(self, run("python", "refit_check.py"), "refit_check.py", "required", "results")
        sc.one_line_error(self, run("python", "exact_ballistic.py"), "exact_ballistic.py", "required", "--out-dir")
        sc.one_line_error(self, run("python", "exact_ballistic.py", "--out-dir"), "exact_ballistic.py",
                          "--out-dir", "expected one argument")
        sc.one_line_error(self, run("tools", "compare_engine_ensembles.py", "a.h5"), "compare_engine_ensembles.py",
                          "required", "B.h5")
        sc.one_line_error(self, run("tools", "reproduce-check"), "reproduce-check", "required", "archive")

    def test_bad_number(self):
        sc.one_line_error(self, run("python", "refit_check.py", "decay.h5", "--tolerance", "small"), "refit_check.py",
                          "--tolerance", "invalid float value")
        sc.one_line_error(self, run("python", "sticky_pav.py", "--N", "many"), "sticky_pav.py", "--N",
                          "invalid int value")
        sc.one_line_error(self, run("tools", "reproduce-check", "archive.tar.gz", "--jobs", "all"), "reproduce-check",
                          "--jobs", "invalid int value")

    def test_exact_ballistic_d_must_be_finite_and_positive(self):
        out_dir = os.path.join(WORK, "theory_bad_d")
        for value in BAD_D:
            with self.subTest(D=value):
                result = run("python", "exact_ballistic.py", "--out-dir", out_dir, "--D=" + value)
                sc.one_line_error(self, result, "exact_ballistic.py", "--D", "finite and > 0")
                self.assertFalse(os.path.exists(out_dir), "--D %s made %s" % (value, out_dir))

    def test_bad_choice(self):
        sc.one_line_error(self, run("python", "reference_gas.py", "start.h5", "--subthreshold", "bouncy"),
                          "reference_gas.py", "--subthreshold", "invalid choice", "elastic")

    def test_a_message_of_several_lines_is_one(self):
        code = "from shockgas.cli import fail; fail('first\\nsecond', 'some_script.py')"
        result = sc.run([sc.PYTHON, "-c", code], cwd=WORK)
        line = sc.one_line_error(self, result, "some_script.py")
        self.assertEqual(line, "some_script.py: error: first second")


class Help(unittest.TestCase):
    def test_help_is_argparse_help(self):
        for folder, name in ARGPARSE_SCRIPTS:
            with self.subTest(script=name):
                result = run(folder, name, "--help")
                self.assertEqual(result.returncode, 0, result.stderr)
                self.assertEqual(result.stderr, "")
                self.assertTrue(result.stdout.startswith(f"usage: {name} "), result.stdout[:300])
                self.assertIn("-h, --help", result.stdout)

    def test_fidelity_report_help(self):
        for words in (["--help"], ["-h"], ["build", "paper", "--help"]):
            with self.subTest(words=words):
                result = run("tools", "fidelity_report.py", *words)
                self.assertEqual(result.returncode, 0, result.stderr)
                self.assertEqual(result.stderr, "")
                self.assertTrue(result.stdout.startswith("usage: fidelity_report.py [-h] BUILD_DIR [quick|paper] "),
                                result.stdout[:300])
                for word in ("-h, --help", "--readme", "--check-readme README.md", "--progress", "BUILD_DIR"):
                    self.assertIn(word, result.stdout)


if __name__ == "__main__":
    os.makedirs(WORK, exist_ok=True)
    unittest.main(verbosity=2)
