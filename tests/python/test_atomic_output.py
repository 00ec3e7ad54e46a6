#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Every output of the Python scripts is written whole or not at all (ctest python.atomic_output,
label python; about 3 s of CPU, most of it starting Python with numpy).

    test_atomic_output.py WORK_DIR

  * The scripts wrote their outputs in place (open(path, "w"), then the rows): an interruption
    mid-write (Ctrl-C, a full disk, an exception) left a truncated file where a whole previous one
    had been. Played here by a file-size limit in a child process (FILE_SIZE_LIMIT: the write fails
    with EFBIG, "File too large", at that size as it would on a full disk): sticky_pav.py
    --clusters-out as a user runs it, and --json, --hist-dir and exact_ballistic.py --out-dir with
    the exact theory's quadratures (seconds) replaced by a stand-in (THEORY_STAND_IN), since what is
    tested is their writing. The previous file was truncated to the limit; now it is as it was, no
    temporary file is left, and the refusal is the one line, exit 2. The table writer of
    exact_ballistic.py and sticky_pav.py's --json, interrupted by KeyboardInterrupt in this
    process, likewise.
  * shockgas.cli.atomic_output and atomic_output_path, which they now write through (as the C++
    programs write through shockgas::TextFile): an exception or KeyboardInterrupt in the block, a
    failing fsync or rename; a symbolic link to a file has the file it points to replaced, the link
    stays a link (a chain of them too); /dev/null stays a device, and /dev/stdout redirected to a
    file with `>>` keeps what the file held and what the script printed before (the same inode: not
    renamed over, and appended to, not truncated); the permissions are those open() gives, the
    umask's for a new file, an existing file's own (tempfile.mkstemp would give 0600); a file that
    may not be written is refused as open() refuses it (not as root).
  * shockgas.cli.output_file_problem: an existing file in a directory that may not be written was
    let through, and its writing, which now makes a file beside it, would fail after the work: now
    refused before it (not as root).
"""
import errno
import io
import os
import resource
import shutil
import stat
import subprocess
import unittest
from unittest import mock

import script_checks as sc

numpy, h5py = sc.require("numpy", "h5py")

WORK = sc.arguments(1)
import exact_ballistic  # noqa: E402
import sticky_pav  # noqa: E402
import shockgas  # noqa: E402
from shockgas import cli  # noqa: E402

# The child's file-size limit (ulimit -f), in bytes: a write past it fails with EFBIG (Python
# ignores SIGXFSZ, which would kill the process). Every output written below is larger.
FILE_SIZE_LIMIT = 1024
PREVIOUS = "# the previous output, whole\n"

# Runs sticky_pav.py or exact_ballistic.py (argv[1], the rest its arguments) as its main() does,
# with the exact theory's slow quadratures (~8 s) replaced by a smooth stand-in: the numbers the
# outputs hold do not matter here, their writing does.
THEORY_STAND_IN = r"""
import os, sys
import numpy as np
from unittest import mock
import exact_ballistic, sticky_pav

def smooth(x, *rest):
    return np.exp(-np.asarray(x, dtype=float) ** 2)

constants = dict(kappa=0.21, nu=1.9, kurtosis=3.0, tail_constant_c=0.5,
                 scaled=dict(N_s=1.0, mass_sum_rule=1.0, resolution_change={}))
sys.argv[0] = sys.argv.pop(1)
with mock.patch.object(exact_ballistic, "compute_constants", return_value=constants), \
        mock.patch.object(exact_ballistic, "phi", smooth), \
        mock.patch.object(exact_ballistic, "mass_density_from_grid", smooth):
    sys.exit({"sticky_pav.py": sticky_pav, "exact_ballistic.py": exact_ballistic}[sys.argv[0]].main(sys.argv[1:]))
"""


def fresh(name):
    directory = os.path.join(WORK, name)
    shutil.rmtree(directory, ignore_errors=True)
    os.makedirs(directory)
    return directory


def previous(path):
    with open(path, "w") as handle:
        handle.write(PREVIOUS)
    return path


def text(path):
    with open(path) as handle:
        return handle.read()


def temporaries(*directories):
    """Files a writer left beside its outputs: anything named *.tmp.*."""
    return sorted(name for directory in directories for name in os.listdir(directory) if ".tmp." in name)


def limit_file_size():
    resource.setrlimit(resource.RLIMIT_FSIZE, (FILE_SIZE_LIMIT, resource.getrlimit(resource.RLIMIT_FSIZE)[1]))


def run_limited(command, cwd):
    """The command in a child whose file-size limit is FILE_SIZE_LIMIT, the source tree's python/ on
    PYTHONPATH."""
    return subprocess.run([str(c) for c in command], cwd=cwd, capture_output=True, text=True,
                          preexec_fn=limit_file_size, env=dict(os.environ, PYTHONPATH=sc.script("python")))


def with_stand_in(name, *arguments):
    return [sc.PYTHON, "-c", THEORY_STAND_IN, name, *arguments]


class InterruptedScripts(unittest.TestCase):
    """A script whose writing fails midway leaves the previous output whole, and no temporary file."""

    def assert_intact(self, result, name, option, *outputs):
        """Exit 2, no traceback, the last stderr line the refusal (an ensemble prints its progress
        above it), each output as it was, no temporary file."""
        described = f"exit {result.returncode}\nstderr: {result.stderr[-2000:]}"
        self.assertEqual(result.returncode, 2, described)
        self.assertNotIn("Traceback", result.stderr, described)
        last = result.stderr.strip().splitlines()[-1]
        self.assertTrue(last.startswith(f"{name}: error: cannot write {option} "), described)
        self.assertTrue(last.endswith(": File too large"), described)
        for output in outputs:
            self.assertEqual(text(output), PREVIOUS, output)
        self.assertEqual(temporaries(*{os.path.dirname(output) for output in outputs}), [])

    def test_sticky_pav_clusters_out(self):
        # As a user runs it: 400 particles, two times, ~20 kB of clusters.
        directory = fresh("clusters_out")
        start = os.path.join(directory, "start.txt")
        velocities = numpy.random.default_rng(1).uniform(-1.0, 1.0, 400)
        with open(start, "w") as handle:
            handle.write("# L = 400\n" + "".join(f"{i} {v}\n" for i, v in enumerate(velocities)))
        output = previous(os.path.join(directory, "clusters.txt"))
        result = run_limited([sc.PYTHON, sc.script("python", "sticky_pav.py"), "--init", start, "--times", 1, 2,
                              "--clusters-out", output], directory)
        self.assert_intact(result, "sticky_pav.py", "--clusters-out", output)

    def test_sticky_pav_json_and_hist_dir(self):
        directory = fresh("compare_outputs")
        ensemble = ("--N", 2000, "--realizations", 2, "--seed", 2, "--times", 100, 200, 400, "--compare")
        json_output = previous(os.path.join(directory, "compare.json"))
        self.assert_intact(run_limited(with_stand_in("sticky_pav.py", *ensemble, "--json", json_output), directory),
                           "sticky_pav.py", "--json", json_output)
        hist = os.path.join(directory, "hist")
        os.makedirs(hist)
        table = previous(os.path.join(hist, "phi_t100.dat"))  # the first the run writes
        self.assert_intact(run_limited(with_stand_in("sticky_pav.py", *ensemble, "--hist-dir", hist), directory),
                           "sticky_pav.py", "--hist-dir", table)

    def test_exact_ballistic_out_dir(self):
        directory = fresh("theory")
        tables = [previous(os.path.join(directory, name)) for name in
                  ("phi.dat", "phi_tail.dat", "mass_distribution.dat", "constants.json", "constants.gp")]
        self.assert_intact(run_limited(with_stand_in("exact_ballistic.py", "--out-dir", directory), directory),
                           "exact_ballistic.py", "--out-dir", *tables)
        # And, without the limit, every one of them is written.
        written = sc.run(with_stand_in("exact_ballistic.py", "--out-dir", directory), cwd=directory,
                         env=dict(os.environ, PYTHONPATH=sc.script("python")))
        self.assertEqual(written.returncode, 0, written.stderr)
        for table in tables:
            self.assertNotEqual(text(table), PREVIOUS, table)
        self.assertEqual(temporaries(directory), [])

    def test_ctrl_c_in_the_table_writer(self):
        # exact_ballistic.py's table writer, interrupted after a few rows (a column that raises).
        directory = fresh("ctrl_c_table")
        output = previous(os.path.join(directory, "phi.dat"))

        def rows():
            yield from range(5)
            raise KeyboardInterrupt

        with self.assertRaises(KeyboardInterrupt):
            exact_ballistic._write_table(output, ["header"], [numpy.arange(10.0), rows()], ["z", "phi"])
        self.assertEqual(text(output), PREVIOUS)
        self.assertEqual(temporaries(directory), [])

    def test_ctrl_c_in_sticky_pav_json(self):
        directory = fresh("ctrl_c_json")
        output = previous(os.path.join(directory, "compare.json"))

        def half_then_ctrl_c(value, handle, **options):
            handle.write('{"N": 2000, "rows": [')
            raise KeyboardInterrupt

        constants = dict(kappa=0.21, nu=1.9, kurtosis=3.0)
        with mock.patch.object(exact_ballistic, "compute_constants", return_value=constants), \
                mock.patch.object(sticky_pav.json, "dump", side_effect=half_then_ctrl_c), \
                mock.patch("sys.stdout", io.StringIO()), mock.patch("sys.stderr", io.StringIO()):
            with self.assertRaises(KeyboardInterrupt):
                sticky_pav.main(["--N", "2000", "--realizations", "2", "--times", "100", "200", "400", "--compare",
                                 "--json", output])
        self.assertEqual(text(output), PREVIOUS)
        self.assertEqual(temporaries(directory), [])


class AtomicOutput(unittest.TestCase):
    """shockgas.cli.atomic_output and atomic_output_path, in this process."""

    def setUp(self):
        self.dir = fresh("atomic_output")

    def test_an_error_in_the_block_leaves_the_previous_file(self):
        for error in (KeyboardInterrupt(), RuntimeError("mid-write"), OSError(errno.ENOSPC, "No space left on device")):
            with self.subTest(error=repr(error)):
                output = previous(os.path.join(self.dir, "out.txt"))
                with self.assertRaises(type(error)):
                    with cli.atomic_output(output) as handle:
                        handle.write("half of the new")
                        raise error
                self.assertEqual(text(output), PREVIOUS)
                self.assertEqual(temporaries(self.dir), [])

    def test_a_new_file_interrupted_leaves_nothing(self):
        output = os.path.join(self.dir, "new.txt")
        with self.assertRaises(KeyboardInterrupt):
            with cli.atomic_output(output) as handle:
                handle.write("half")
                raise KeyboardInterrupt
        self.assertEqual(os.listdir(self.dir), [])

    def test_a_failing_sync_or_rename_names_the_output(self):
        for step in ("fsync", "replace"):
            with self.subTest(step=step):
                output = previous(os.path.join(self.dir, "out.txt"))
                full = OSError(errno.ENOSPC, "No space left on device")
                with mock.patch.object(cli.os, step, side_effect=full), self.assertRaises(OSError) as raised:
                    with cli.atomic_output(output) as handle:
                        handle.write("new\n")
                self.assertEqual((raised.exception.errno, raised.exception.filename), (errno.ENOSPC, output))
                self.assertEqual(text(output), PREVIOUS)
                self.assertEqual(temporaries(self.dir), [])

    def test_written_whole(self):
        output = previous(os.path.join(self.dir, "out.txt"))
        before = os.stat(output).st_ino
        with cli.atomic_output(output) as handle:
            handle.write("new\n")
            self.assertEqual(text(output), PREVIOUS)  # until the block ends
        self.assertEqual(text(output), "new\n")
        self.assertNotEqual(os.stat(output).st_ino, before)  # renamed onto it, not written in place
        with cli.atomic_output(output, "wb") as handle:
            handle.write(b"\x00\x01")
        with open(output, "rb") as handle:
            self.assertEqual(handle.read(), b"\x00\x01")
        with self.assertRaises(ValueError):
            with cli.atomic_output(output, "a"):
                pass
        self.assertEqual(temporaries(self.dir), [])

    def test_hdf5_through_a_temporary_name(self):
        output = os.path.join(self.dir, "out.h5")
        with h5py.File(output, "w") as handle:
            handle["x"] = numpy.arange(3.0)
        with self.assertRaises(KeyboardInterrupt):
            with cli.atomic_output_path(output) as name:
                with h5py.File(name, "w") as handle:
                    handle["x"] = numpy.arange(5.0)
                raise KeyboardInterrupt
        with shockgas.open_file(output, check_schema=False) as handle:
            self.assertEqual(len(handle["x"]), 3)
        with cli.atomic_output_path(output) as name:
            with h5py.File(name, "w") as handle:
                handle["x"] = numpy.arange(5.0)
        with shockgas.open_file(output, check_schema=False) as handle:
            self.assertEqual(len(handle["x"]), 5)
        self.assertEqual(temporaries(self.dir), [])

    def test_symbolic_links(self):
        # links/relative -> ../files/real.txt, links/absolute -> links/relative: the file is replaced,
        # beside itself, and both links stay links, pointing where they did.
        files, links = os.path.join(self.dir, "files"), os.path.join(self.dir, "links")
        os.makedirs(files)
        os.makedirs(links)
        real = previous(os.path.join(files, "real.txt"))
        relative, absolute = os.path.join(links, "relative"), os.path.join(links, "absolute")
        os.symlink(os.path.join("..", "files", "real.txt"), relative)
        os.symlink(os.path.abspath(relative), absolute)
        self.assertEqual(cli.replaced_file(absolute), os.path.join(links, "..", "files", "real.txt"))
        with self.assertRaises(KeyboardInterrupt):
            with cli.atomic_output(absolute) as handle:
                handle.write("half")
                raise KeyboardInterrupt
        self.assertEqual(text(real), PREVIOUS)
        before = os.stat(real).st_ino
        with cli.atomic_output(absolute) as handle:
            handle.write("new\n")
        self.assertEqual(text(real), "new\n")
        self.assertNotEqual(os.stat(real).st_ino, before)  # replaced, not written through the link
        self.assertEqual(os.readlink(relative), os.path.join("..", "files", "real.txt"))
        self.assertEqual(os.readlink(absolute), os.path.abspath(relative))
        self.assertEqual(temporaries(files, links), [])
        # A link to nothing is written through (the file it names is made), as open() does.
        dangling = os.path.join(links, "dangling")
        os.symlink("made.txt", dangling)
        self.assertIsNone(cli.replaced_file(dangling))
        with cli.atomic_output(dangling) as handle:
            handle.write("made\n")
        self.assertTrue(os.path.islink(dangling))
        self.assertEqual(text(os.path.join(links, "made.txt")), "made\n")

    def test_devices_are_written_through(self):
        for device in ("/dev/null", "/dev/stdout", "/dev/stderr", "/proc/self/fd/1"):
            self.assertIsNone(cli.replaced_file(device), device)
        with cli.atomic_output(os.devnull) as handle:
            handle.write("gone\n")
        self.assertTrue(stat.S_ISCHR(os.stat(os.devnull).st_mode))

    def test_dev_stdout_redirected_with_append(self):
        # A script that prints, then writes its output to /dev/stdout, run as `script >> log`.
        log = previous(os.path.join(self.dir, "log.txt"))
        before = os.stat(log).st_ino
        script = ("from shockgas import cli\nprint('printed first')\n"
                  "with cli.atomic_output('/dev/stdout') as handle:\n    handle.write('the output\\n')\n")
        with open(log, "a") as appended:
            result = subprocess.run([sc.PYTHON, "-c", script], stdout=appended, stderr=subprocess.PIPE, text=True,
                                    env=dict(os.environ, PYTHONPATH=sc.script("python")))
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(text(log), PREVIOUS + "printed first\nthe output\n")
        self.assertEqual(os.stat(log).st_ino, before)
        self.assertEqual(temporaries(self.dir), [])

    def test_dev_stdout_redirected_without_append(self):
        # `script > log`: the shell's descriptor has its own offset, which a second open of /dev/stdout
        # would not share, so what the script prints after its output would overwrite it.
        log = os.path.join(self.dir, "log.txt")
        script = ("import sys\nfrom shockgas import cli\nprint('printed first')\n"
                  "with cli.atomic_output('/dev/stdout') as handle:\n    handle.write('the output\\n')\n"
                  "print('printed after')\n")
        with open(log, "w") as truncated:
            result = subprocess.run([sc.PYTHON, "-c", script], stdout=truncated, stderr=subprocess.PIPE, text=True,
                                    env=dict(os.environ, PYTHONPATH=sc.script("python")))
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(text(log), "printed first\nthe output\nprinted after\n")

    def test_permissions_are_what_open_gives(self):
        umask = os.umask(0o027)
        try:
            new = os.path.join(self.dir, "new.txt")
            with cli.atomic_output(new) as handle:
                handle.write("new\n")
            self.assertEqual(stat.S_IMODE(os.stat(new).st_mode), 0o640)  # 0666 less the umask
            existing = previous(os.path.join(self.dir, "existing.txt"))
            os.chmod(existing, 0o604)
            with cli.atomic_output(existing) as handle:
                handle.write("new\n")
            self.assertEqual(stat.S_IMODE(os.stat(existing).st_mode), 0o604)  # its own, as open() keeps them
        finally:
            os.umask(umask)

    def test_a_file_that_may_not_be_written_is_refused(self):
        if os.geteuid() == 0:
            self.skipTest("run as root, who may write any file")
        output = previous(os.path.join(self.dir, "locked.txt"))
        os.chmod(output, 0o444)
        with self.assertRaises(PermissionError) as raised:
            with cli.atomic_output(output) as handle:
                handle.write("new\n")
        self.assertEqual(raised.exception.filename, output)
        self.assertEqual(text(output), PREVIOUS)
        self.assertEqual(temporaries(self.dir), [])


class OutputFileProblem(unittest.TestCase):
    def test_a_file_whose_directory_may_not_be_written(self):
        if os.geteuid() == 0:
            self.skipTest("run as root, who may write in a read-only directory")
        directory = fresh("locked_directory")
        output = previous(os.path.join(directory, "out.txt"))
        elsewhere = os.path.join(WORK, "link_into_locked_directory")
        if os.path.lexists(elsewhere):
            os.remove(elsewhere)
        os.symlink(output, elsewhere)
        os.chmod(directory, 0o555)
        try:
            for path in (output, elsewhere):
                with self.subTest(path=path):
                    self.assertEqual(cli.output_file_problem(path), "Permission denied")
        finally:
            os.chmod(directory, 0o755)


if __name__ == "__main__":
    os.makedirs(WORK, exist_ok=True)
    unittest.main(verbosity=2)
