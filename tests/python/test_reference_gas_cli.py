#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""python/reference_gas.py as a user runs it (ctest python.reference_gas_inputs, label python; < 1 s).

    test_reference_gas_cli.py SIM WORK_DIR

  * --compare RUN.h5 checks the run was made from the init file given: the run records its start's
    SHA-256 (init_file_sha256). A start differing in one velocity, and a run made from no init file,
    are refused (exit 2, one line); before, they were compared and showed differences that were no
    engine's fault. The run's own start is compared (exit 0, the reference's T beside the run's).
  * A bad value on the command line (r outside [0, 1], delta < 0 or NaN, --digits 0, --sample-times abc,
    a time outside [0, t_max], t_max <= 0, --max-events < 1, ...) is one line naming the option, exit 2,
    nothing on stdout, before the init file is read: before, -r 1.5, -d -1, --digits 0 and
    --sample-times abc ended in a ValueError traceback (exit 1), -t -5 printed a row at t = -5 and
    --max-events -3 rows of NaN (exit 0), --sample-times nan never ended. A start that simulate()
    refuses (positions not sorted) is one line naming the file, not simulate()'s traceback. So is a
    malformed start (ring_length an array or a string, position a group, a 2-D or scalar dataset,
    strings; script_checks.MALFORMED_STARTS): ring_length an array and position a group were
    TypeError tracebacks from shockgas.read_initial_condition.
  * A python3 without h5py: one line naming the missing module and /usr/bin/python3, exit 2 (it
    was a ModuleNotFoundError traceback). Run here with a stand-in h5py on PYTHONPATH that fails to
    import, as a machine without python3-h5py does.
  * docs/reference-check.md runs the script with /usr/bin/python3, as the other docs do, not with
    whatever python3 is first on the PATH.
"""
import os
import subprocess
import sys
import unittest

import script_checks as sc

try:
    import h5py
    import numpy  # noqa: F401
except ImportError as error:  # pragma: no cover
    print("SKIP: needs numpy and h5py (%s)" % error)
    sys.exit(77)
# python/shockgas from PYTHONPATH (ctest's): missing, the test fails rather than skips.
import shockgas  # noqa: E402

SIM, WORK = sc.arguments(2)
TOOL = sc.script("python", "reference_gas.py")
NAME = "reference_gas.py"
# The reference and shockgas-sim on a 4-particle start agree to rounding (docs/reference-check.md:
# within 3.8e-15 relative in T on every case); 1e-12 is far above that and far below any real
# difference (another start's T differs at the first collision by percents).
T_RELATIVE_TOLERANCE = 1e-12


def path(name):
    return os.path.join(WORK, name)


class Compare(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        os.makedirs(WORK, exist_ok=True)
        position = [0.0, 1.5, 3.0, 4.2]
        shockgas.write_initial_condition(path("start.h5"), position, [0.5, -0.2, 0.3, -0.6], ring_length=5.0,
                                         overwrite=True)
        shockgas.write_initial_condition(path("other_start.h5"), position, [0.5, -0.2, 0.3, -0.61], ring_length=5.0,
                                         overwrite=True)
        for name, options in (("run.h5", ["--init", path("start.h5"), "-R", 1]),
                              ("generated.h5", ["-N", 4, "--ring-length", 5.0, "-R", 1])):
            result = sc.run([SIM, *options, "-r", 0.5, "-d", 0.01, "-t", 20, "-q", "-o", path(name)], cwd=WORK)
            assert result.returncode == 0, result.stderr

    def test_the_runs_own_start_is_compared(self):
        result = sc.run([sc.PYTHON, TOOL, path("start.h5"), "--compare", path("run.h5")], cwd=WORK)
        self.assertEqual(result.returncode, 0, result.stderr)
        rows = [line.split() for line in result.stdout.splitlines() if line and line[0].isdigit()]
        self.assertGreater(len(rows), 10)
        for row in rows:  # t T K clusters collisions/N | T K clusters collisions/N
            reference, simulated = float(row[1]), float(row[6])
            self.assertLessEqual(abs(reference - simulated), T_RELATIVE_TOLERANCE * abs(reference), row)

    def test_another_start_is_refused(self):
        result = sc.run([sc.PYTHON, TOOL, path("other_start.h5"), "--compare", path("run.h5")], cwd=WORK)
        sc.one_line_error(self, result, NAME, "is not the initial condition", "init_file_sha256")

    def test_a_run_without_an_init_file_is_refused(self):
        result = sc.run([sc.PYTHON, TOOL, path("start.h5"), "--compare", path("generated.h5")], cwd=WORK)
        sc.one_line_error(self, result, NAME, "not made from an init file")

    def test_bad_files(self):
        sc.one_line_error(self, sc.run([sc.PYTHON, TOOL, path("no_such.h5")], cwd=WORK), NAME, "no such file")
        sc.one_line_error(self, sc.run([sc.PYTHON, TOOL, path("run.h5")], cwd=WORK), NAME,
                          "not an initial condition")


    def test_malformed_starts_are_one_line(self):
        # shockgas.read_initial_condition refuses a ring_length holding an array and a position stored as
        # a group in one line naming the item, not with a TypeError (a traceback here).
        for name, words in sc.MALFORMED_STARTS:
            with self.subTest(start=name):
                with h5py.File(path(name + ".h5"), "w") as handle:
                    sc.write_malformed_start(handle, name)
                result = sc.run([sc.PYTHON, TOOL, path(name + ".h5")], cwd=WORK)
                sc.one_line_error(self, result, NAME, name + ".h5", *words)
                self.assertEqual(result.stdout, "")

# Each bad command line (options after the init file) and words its one error line must hold; run with
# a timeout, as --sample-times nan ran forever.
BAD_ARGUMENTS = [
    (["-r", "1.5"], ["--restitution", "1.5", "[0, 1]"]),
    (["-r", "nan"], ["--restitution", "nan"]),
    (["-d", "-1"], ["--threshold", "-1.0", ">= 0"]),
    (["-d", "nan"], ["--threshold", "nan"]),
    (["--digits", "0"], ["--digits 0"]),
    (["--sample-times", "abc"], ["--sample-times", "'abc' is not a number"]),
    (["--sample-times", "1,nan"], ["--sample-times", "nan", "outside"]),
    (["-t", "10", "--sample-times", "20"], ["--sample-times", "20", "outside [0, t_max = 10.0]"]),
    (["-t", "-5"], ["--t-max", "-5.0", "> 0"]),
    (["-t", "inf"], ["--t-max", "inf"]),
    (["--max-events", "-3"], ["--max-events -3", "at least 1"]),
    (["--max-events", "0"], ["--max-events 0"]),
    (["--samples-per-decade", "0"], ["--samples-per-decade 0"]),
    (["--collapse-speed", "-1"], ["--collapse-speed", "-1.0"]),
    (["-d", "0.01", "--collapse-speed", "0.1"], ["--collapse-speed", "exceeds the threshold"]),
]
# Far above what a refusal takes (the imports, < 1 s), far below ctest's TIMEOUT.
REFUSAL_SECONDS = 30
# A 4-particle start whose positions are not sorted (as shockgas.write_initial_condition refuses to
# write, so written with h5py).
UNSORTED_POSITIONS = [0.0, 3.0, 1.5, 4.2]


class Arguments(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        os.makedirs(WORK, exist_ok=True)
        cls.start = path("arguments_start.h5")
        shockgas.write_initial_condition(cls.start, [0.0, 1.5, 3.0, 4.2], [0.5, -0.2, 0.3, -0.6], ring_length=5.0,
                                         overwrite=True)

    def refuse(self, arguments, words, start=None):
        try:
            result = subprocess.run([sc.PYTHON, TOOL, start or self.start, *arguments], cwd=WORK, capture_output=True,
                                    text=True, timeout=REFUSAL_SECONDS)
        except subprocess.TimeoutExpired:
            self.fail("%s: still running after %d s" % (" ".join(arguments), REFUSAL_SECONDS))
        sc.one_line_error(self, result, NAME, *words)
        self.assertEqual(result.stdout, "", arguments)  # no header, no rows: nothing half done

    def test_bad_values_are_one_line(self):
        for arguments, words in BAD_ARGUMENTS:
            with self.subTest(arguments=arguments):
                self.refuse(arguments, words)

    def test_a_start_simulate_refuses_is_one_line(self):
        unsorted = path("unsorted_start.h5")
        with h5py.File(unsorted, "w") as handle:
            handle.attrs["ring_length"] = 5.0
            handle["position"] = UNSORTED_POSITIONS
            handle["velocity"] = [0.5, -0.2, 0.3, -0.6]
        # Read through shockgas.read_initial_condition, which checks a start as shockgas-sim does.
        self.refuse([], ["unsorted_start.h5", "positions are not sorted", "position[2] = 1.5"], start=unsorted)

    def test_good_values_still_run(self):
        result = sc.run([sc.PYTHON, TOOL, self.start, "-r", "0", "-d", "0", "-t", "5", "--sample-times", "0,2.5,5",
                         "--max-events", "1", "--digits", "20"], cwd=WORK)
        self.assertEqual(result.returncode, 0, result.stderr)
        rows = [line.split() for line in result.stdout.splitlines() if line and line[0].isdigit()]
        self.assertIn(["2.5"], [row[:1] for row in rows])


class Interpreter(unittest.TestCase):
    def test_missing_module_is_one_line(self):
        fake = path("without_h5py")
        os.makedirs(os.path.join(fake, "h5py"), exist_ok=True)
        with open(os.path.join(fake, "h5py", "__init__.py"), "w") as handle:
            handle.write("raise ModuleNotFoundError(\"No module named 'h5py'\", name='h5py')\n")
        env = dict(os.environ, PYTHONPATH=fake)
        result = sc.run([sc.PYTHON, TOOL, path("start.h5")], cwd=WORK, env=env)
        sc.one_line_error(self, result, NAME, "h5py is missing", "/usr/bin/python3")

    def test_the_documentation_names_the_interpreter(self):
        with open(sc.script("docs", "reference-check.md"), encoding="utf-8") as handle:
            lines = handle.read().splitlines()
        bare = [line for line in lines if line.lstrip().startswith("python3 ") or "`python3 " in line]
        self.assertEqual(bare, [])
        self.assertGreaterEqual(sum("/usr/bin/python3 python/reference_gas.py" in line for line in lines), 3)


if __name__ == "__main__":
    os.makedirs(WORK, exist_ok=True)
    unittest.main(verbosity=2)
