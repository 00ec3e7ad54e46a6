# SPDX-License-Identifier: GPL-3.0-or-later
"""Helpers for the tests of the project's Python scripts as a user runs them (tests/python/test_*_cli.py).

A user's mistake must give exit status 2 and one line "<script>: error: <what>" on stderr, never a
Python traceback (house rule; exit 1 is kept for what a script's documentation gives it).
"""
import os
import subprocess
import sys

SOURCE = os.path.realpath(os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", ".."))
PYTHON = sys.executable  # the interpreter ctest runs the test with (SHOCKGAS_PYTHON): numpy, scipy, h5py


SKIP = 77  # the tests' SKIP_RETURN_CODE (tests/python/python_tests.cmake)


def require(*modules):
    """Imports each module and returns them in order; when one is missing (a machine without Debian's
    python3-numpy, -scipy or -h5py) prints "SKIP: needs a, b and c (<why>)" and exits SKIP, so ctest
    reports the test skipped rather than failed."""
    import importlib
    try:
        return [importlib.import_module(name) for name in modules]
    except ImportError as error:  # pragma: no cover - depends on the machine
        names = ", ".join(modules[:-1]) + " and " + modules[-1] if len(modules) > 1 else modules[0]
        print("SKIP: needs %s (%s)" % (names, error))
        sys.exit(SKIP)


def arguments(count):
    """The test's own `count` leading arguments (programs, the work directory), taken off sys.argv so
    that unittest.main() reads only its own."""
    taken = sys.argv[1:1 + count]
    del sys.argv[1:1 + count]
    return taken[0] if count == 1 else taken


def script(*relative):
    return os.path.join(SOURCE, *relative)


def run(command, cwd=None, env=None):
    """Runs a command (strings or numbers) and returns the CompletedProcess, output captured as text."""
    return subprocess.run([str(c) for c in command], cwd=cwd, env=env, capture_output=True, text=True)


def one_line_error(test, result, name, *words):
    """Asserts exit status 2, no traceback, and exactly one stderr line "<name>: error: ..." holding
    every one of `words`."""
    described = f"exit {result.returncode}\nstdout: {result.stdout[-2000:]}\nstderr: {result.stderr[-2000:]}"
    test.assertEqual(result.returncode, 2, described)
    test.assertNotIn("Traceback", result.stderr, described)
    lines = result.stderr.strip().splitlines()
    test.assertEqual(len(lines), 1, described)
    test.assertTrue(lines[0].startswith(f"{name}: error: "), described)
    for word in words:
        test.assertIn(word, lines[0], described)
    return lines[0]


# HDF5 starts of the --init format gone wrong, each with the words its one error line must hold (not a
# TypeError traceback, as for ring_length an array or position a group, nor a message naming none of
# them, as for 2-D).
MALFORMED_STARTS = [
    ("ring_length_array", ["ring_length holds 2 values", "single number"]),
    ("ring_length_string", ["ring_length is a string", "single number"]),
    ("position_group", ["position is a group, not a dataset"]),
    ("position_2d", ["position is a dataset of shape (2, 2)", "one-dimensional"]),
    ("velocity_2d", ["velocity is a dataset of shape (4, 1)", "one-dimensional"]),
    ("mass_scalar", ["mass is a dataset of shape ()", "one-dimensional"]),
    ("position_strings", ["position holds", "not numbers"]),
]


def write_malformed_start(handle, name):
    """Writes the start MALFORMED_STARTS names into the open h5py file `handle`: a good one, then one item spoiled."""
    handle.attrs["ring_length"] = 5.0
    handle["position"] = [0.0, 1.5, 3.0, 4.2]
    handle["velocity"] = [0.5, -0.2, 0.3, -0.6]
    item = name.split("_")[0] if not name.startswith("ring_length") else "ring_length"
    if item == "ring_length":
        handle.attrs["ring_length"] = [5.0, 6.0] if name.endswith("array") else "five"
        return
    if item in handle:
        del handle[item]
    if name == "position_group":
        handle.create_group("position").create_dataset("x", data=[0.0, 1.5, 3.0, 4.2])
    elif name == "position_2d":
        handle["position"] = [[0.0, 1.5], [3.0, 4.2]]
    elif name == "velocity_2d":
        handle["velocity"] = [[0.5], [-0.2], [0.3], [-0.6]]
    elif name == "mass_scalar":
        handle["mass"] = 1.0
    elif name == "position_strings":
        handle["position"] = [b"0", b"1.5", b"3", b"4.2"]
