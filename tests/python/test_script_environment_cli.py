#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""What the machine gives a script, refused in one line (ctest python.script_environment, label
python; about 3 s of CPU, most of it starting Python with numpy and h5py): a package or the shockgas
module missing, an output path that cannot be written.

    test_script_environment_cli.py WORK_DIR

  * numpy or h5py missing, played by a stand-in on PYTHONPATH that fails to import as a missing
    package does: tools/reproduce-check and exact_ballistic.py (without numpy) give one line naming
    the package and /usr/bin/python3, exit 2, as fidelity_report.py does, not a ModuleNotFoundError
    traceback. refit_check.py exits 77 there (ctest's python.refit_check skips on a machine without
    them, SKIP_RETURN_CODE 77), naming the package that is missing.
  * the shockgas module missing: a copy of the script where an installation puts it
    (<prefix>/share/shockgas/python or tools, with no python/shockgas beside it) run without
    PYTHONPATH, as when the module went to another prefix's module folder (where a shockgas module
    is installed on this Python's own path, a stand-in beside the copies fails as a missing one
    does): one line naming the module and PYTHONPATH, exit 2. Not a traceback (reproduce-check),
    nor "SKIP: refit_check.py needs numpy, scipy and h5py (No module named 'shockgas')" and exit 77
    with all three installed (refit_check.py), nor "shockgas is missing (needs numpy and h5py): run
    it with Debian's /usr/bin/python3" (fidelity_report.py and reference_gas.py).
  * an output that cannot be written: exact_ballistic.py --out-dir, reproduce-check --work-dir and
    pack --output-dir given a file, or a path under a file (and a read-only directory, when not run
    as root, who may write there): one line naming the option, the path and the cause, before the
    work, not a traceback (FileExistsError, NotADirectoryError). shockgas.cli's checks, which
    they and sticky_pav.py share (tests/python/test_sticky_pav_cli.py), directly: what they refuse,
    what they let through, and that they leave nothing behind.
"""
import os
import shutil
import unittest

import script_checks as sc

sc.require("h5py", "numpy", "scipy")

WORK = sc.arguments(1)
from shockgas import cli  # noqa: E402


def path(*parts):
    return os.path.join(WORK, *parts)


def without_pythonpath():
    return {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}


def stand_in(package):
    """A folder for PYTHONPATH holding `package` that fails to import as a missing one does."""
    folder = path("without_" + package)
    os.makedirs(os.path.join(folder, package), exist_ok=True)
    with open(os.path.join(folder, package, "__init__.py"), "w") as handle:
        handle.write(f"raise ModuleNotFoundError(\"No module named '{package}'\", name='{package}')\n")
    return folder


def run_with(package, folder, name, *arguments):
    """Runs a script of the source tree with `package` missing."""
    return sc.run([sc.PYTHON, sc.script(folder, name), *arguments], cwd=WORK,
                  env=dict(os.environ, PYTHONPATH=stand_in(package)))


class MissingPackages(unittest.TestCase):
    def test_one_line_naming_the_package(self):
        for package, folder, name in [("h5py", "tools", "reproduce-check"), ("numpy", "tools", "reproduce-check"),
                                      ("h5py", "tools", "fidelity_report.py"),
                                      ("numpy", "python", "exact_ballistic.py")]:
            with self.subTest(script=name, package=package):
                arguments = ["--out-dir", path("theory")] if name == "exact_ballistic.py" else ["x"]
                sc.one_line_error(self, run_with(package, folder, name, *arguments), name,
                                  f"{package} is missing", "/usr/bin/python3")

    def test_refit_check_skips_naming_the_package(self):
        for package in ("h5py", "numpy", "scipy"):
            with self.subTest(package=package):
                result = run_with(package, "python", "refit_check.py", "decay.h5")
                self.assertEqual(result.returncode, 77, result.stdout + result.stderr)  # ctest's SKIP_RETURN_CODE
                self.assertNotIn("Traceback", result.stderr)
                self.assertIn(f"SKIP: refit_check.py needs numpy, scipy and h5py: {package} is missing", result.stdout)


class MissingModule(unittest.TestCase):
    """The scripts where an installation puts them, the module not on Python's path."""

    @classmethod
    def setUpClass(cls):
        cls.share = path("prefix", "share", "shockgas")
        shutil.rmtree(path("prefix"), ignore_errors=True)
        # As cmake/Install.cmake lays them out: the scripts in tools/ with tools/shockgas_path.py.
        for folder, name in [("python", "refit_check.py"), ("python", "reference_gas.py"),
                             ("tools", "reproduce-check"), ("tools", "fidelity_report.py"),
                             ("tools", "shockgas_path.py")]:
            os.makedirs(os.path.join(cls.share, folder), exist_ok=True)
            shutil.copy2(sc.script(folder, name), os.path.join(cls.share, folder, name))
        # Installed on this Python's own path (a .deb's /usr/lib/python3/dist-packages), the module
        # would be found: then a stand-in beside the copies, found first, fails as a missing one does.
        found = sc.run([sc.PYTHON, "-c", "import importlib.util, sys; sys.exit(importlib.util.find_spec('shockgas') "
                        "is not None)"], cwd=cls.share, env=without_pythonpath())
        if found.returncode != 0:
            module = os.path.join(cls.share, "python", "shockgas")
            os.makedirs(module)
            with open(os.path.join(module, "__init__.py"), "w") as handle:
                handle.write("raise ModuleNotFoundError(\"No module named 'shockgas'\", name='shockgas')\n")

    def run_installed(self, folder, name, *arguments):
        return sc.run([sc.PYTHON, os.path.join(self.share, folder, name), *arguments], cwd=WORK,
                      env=without_pythonpath())

    def test_one_line_naming_the_module(self):
        for folder, name in [("tools", "reproduce-check"), ("python", "refit_check.py"),
                             ("tools", "fidelity_report.py"), ("python", "reference_gas.py")]:
            with self.subTest(script=name):
                line = sc.one_line_error(self, self.run_installed(folder, name, "x"), name,
                                         "Python module shockgas is missing", "PYTHONPATH")
                self.assertNotIn("numpy", line)

    def test_the_source_tree_finds_it(self):
        # Beside the scripts of the source tree: the module is found, and the argument is the refusal.
        sc.one_line_error(self, sc.run([sc.PYTHON, sc.script("tools", "reproduce-check"), path("no-archive.tar.gz")],
                                       cwd=WORK, env=without_pythonpath()), "reproduce-check", "no such file")


def directory_with_a_file(name, text):
    """A fresh directory WORK/name holding one file, plain.txt, with `text`: (directory, file)."""
    directory = path(name)
    shutil.rmtree(directory, ignore_errors=True)
    os.makedirs(directory)
    plain = os.path.join(directory, "plain.txt")
    with open(plain, "w") as handle:
        handle.write(text)
    return directory, plain


class Outputs(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir, cls.plain = directory_with_a_file("outputs", "a file\n")

    def script(self, folder, name, *arguments):
        return sc.run([sc.PYTHON, sc.script(folder, name), *arguments], cwd=WORK)

    def test_exact_ballistic_out_dir(self):
        sc.one_line_error(self, self.script("python", "exact_ballistic.py", "--out-dir", self.plain),
                          "exact_ballistic.py", "--out-dir", "plain.txt", "not a directory")
        sc.one_line_error(self, self.script("python", "exact_ballistic.py", "--out-dir", os.path.join(self.plain, "t")),
                          "exact_ballistic.py", "--out-dir", "plain.txt' is not a directory")

    def test_reproduce_check_work_dir(self):
        for work_dir in (self.plain, os.path.join(self.plain, "work")):
            with self.subTest(work_dir=work_dir):
                # The archive is any file: the work directory is made before it is read.
                sc.one_line_error(self, self.script("tools", "reproduce-check", self.plain, "--work-dir", work_dir),
                                  "reproduce-check", "--work-dir", "not a directory")

    def test_reproduce_check_pack_output_dir(self):
        sc.one_line_error(self, self.script("tools", "reproduce-check", "pack", "--build-dir", self.dir, "--source-dir",
                                            self.dir, "--fidelity", "quick", "--figures", "fig1", "--output-dir",
                                            os.path.join(self.plain, "archives")),
                          "reproduce-check pack", "--output-dir", "plain.txt' is not a directory")

    def test_read_only_directory(self):
        if os.geteuid() == 0:
            self.skipTest("run as root, who may write in a read-only directory")
        locked = os.path.join(self.dir, "locked")
        os.makedirs(locked, exist_ok=True)
        os.chmod(locked, 0o555)
        try:
            sc.one_line_error(self, self.script("python", "exact_ballistic.py", "--out-dir", os.path.join(locked, "t")),
                              "exact_ballistic.py", "--out-dir", "Permission denied")
            sc.one_line_error(self, self.script("tools", "reproduce-check", self.plain, "--work-dir", locked),
                              "reproduce-check", "--work-dir", "Permission denied")
            self.assertIsNotNone(cli.output_file_problem(os.path.join(locked, "x.json")))
        finally:
            os.chmod(locked, 0o755)


class Checks(unittest.TestCase):
    """shockgas.cli.output_file_problem and output_directory_problem."""

    def setUp(self):
        self.dir, self.plain = directory_with_a_file("checks", "kept\n")

    def test_file(self):
        missing = os.path.join(self.dir, "missing", "deeper")
        self.assertEqual(cli.output_file_problem(os.path.join(missing, "x.json")),
                         f"directory '{missing}' does not exist")
        self.assertEqual(cli.output_file_problem(os.path.join(self.plain, "x.json")),
                         f"'{self.plain}' is not a directory")
        self.assertEqual(cli.output_file_problem(self.dir), "it is a directory")
        self.assertEqual(cli.output_file_problem(self.dir + os.sep), "it names no file")
        self.assertIsNone(cli.output_file_problem(os.path.join(self.dir, "new.json")))
        self.assertIsNone(cli.output_file_problem(self.plain))  # overwritten when written, untouched now
        self.assertIsNone(cli.output_file_problem(os.devnull))  # not a regular file: its writing will tell
        with open(self.plain) as handle:
            self.assertEqual(handle.read(), "kept\n")
        self.assertEqual(sorted(os.listdir(self.dir)), ["plain.txt"])  # nothing left behind

    def test_directory(self):
        self.assertEqual(cli.output_directory_problem(self.plain), "it exists and is not a directory")
        self.assertEqual(cli.output_directory_problem(os.path.join(self.plain, "a", "b")),
                         f"'{self.plain}' is not a directory")
        self.assertIsNone(cli.output_directory_problem(self.dir))
        self.assertIsNone(cli.output_directory_problem(os.path.join(self.dir, "new", "deeper")))
        self.assertEqual(sorted(os.listdir(self.dir)), ["plain.txt"])  # nothing made, nothing left behind

    def test_the_line(self):
        self.assertEqual(cli.cannot_write("out.json", OSError(28, "No space left on device"), "--json"),
                         "cannot write --json 'out.json': No space left on device")
        self.assertEqual(cli.cannot_write("out", "it is a directory"), "cannot write 'out': it is a directory")
        code = "import sys; from shockgas import cli; cli.check_output_file(sys.argv[1], '--json', 'some_script.py')"
        result = sc.run([sc.PYTHON, "-c", code, self.dir], cwd=WORK)
        line = sc.one_line_error(self, result, "some_script.py")
        self.assertEqual(line, f"some_script.py: error: cannot write --json '{self.dir}': it is a directory")


if __name__ == "__main__":
    os.makedirs(WORK, exist_ok=True)
    unittest.main(verbosity=2)
