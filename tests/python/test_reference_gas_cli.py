#!/usr/bin/python3
"""python/reference_gas.py as a user runs it (ctest python.reference_gas_inputs, label python; < 1 s).

    test_reference_gas_cli.py SIM WORK_DIR

  * --compare RUN.h5 checks the run was made from the init file given: the run records its start's
    SHA-256 (init_file_sha256). A start differing in one velocity, and a run made from no init file,
    are refused (exit 2, one line); before, they were compared and showed differences that were no
    engine's fault. The run's own start is compared (exit 0, the reference's T beside the run's).
  * A python3 without h5py: one line naming the missing module and /usr/bin/python3, exit 2 (it
    was a ModuleNotFoundError traceback). Run here with a stand-in h5py on PYTHONPATH that fails to
    import, as a machine without python3-h5py does.
  * docs/reference-check.md runs the script with /usr/bin/python3, as the other docs do, not with
    whatever python3 is first on the PATH.
"""
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
import script_checks as sc  # noqa: E402

try:
    import h5py  # noqa: F401
    import numpy  # noqa: F401

    sys.path.insert(0, sc.script("python"))
    import shockgas
except ImportError as error:  # pragma: no cover
    print("SKIP: needs numpy and h5py (%s)" % error)
    sys.exit(77)

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
