# SPDX-License-Identifier: GPL-3.0-or-later
"""How the scripts in tools/ find the Python module shockgas: the one place that says so.

A script in tools/ imports this module first (`import shockgas_path`; Python finds it because a
script's own folder heads Python's path). It puts python/ of the same tree (../python beside this
folder) first on Python's path, so that a clone runs the scripts without PYTHONPATH, with its own
module shockgas and python/exact_ballistic.py. An installed copy (<prefix>/share/shockgas/tools, this
file beside the scripts) finds share/shockgas/python there, and the module where `cmake --install`
put it, on Python's path. The scripts in python/ need none of this (the module is in their own
folder), and the tests get PYTHONPATH from ctest.

require(script, module) imports numpy, h5py and the module, or refuses in one line, exit status 2.
"""
import importlib
import os
import sys

PYTHON_DIR = os.path.normpath(os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", "python"))
if PYTHON_DIR not in sys.path:
    sys.path.insert(0, PYTHON_DIR)


def require(script, module="shockgas"):
    """Imports numpy, h5py and `module` (shockgas or one of its submodules). A python3 without numpy
    or h5py, or an installed copy run where the module is not on Python's path (installed at another
    prefix), or a module that does not import: one line "<script>: error: ..." naming what is
    missing, and exit status 2. `script` is the script's name in tools/."""
    try:
        import h5py  # noqa: F401  (the module's own needs, imported here to be named when missing)
        import numpy  # noqa: F401
    except ImportError as error:  # pragma: no cover - depends on the machine
        _refuse(script, f"{error.name or error} is missing (needs numpy and h5py): run it with Debian's "
                        f"/usr/bin/python3 (python3-numpy, python3-h5py)")
    try:
        importlib.import_module(module)
    except ImportError as error:
        if error.name == "shockgas":
            why = (f"the Python module shockgas is missing (not in ../python beside this script, nor on Python's "
                   f"path): set PYTHONPATH to the folder `cmake --install` put it in (such as <prefix>/lib/python"
                   f"{sys.version_info[0]}.{sys.version_info[1]}/site-packages; docs/python.md), or run the source "
                   f"tree's tools/{script}")
        else:
            why = f"the Python module shockgas does not import ({error}): another version of it on Python's path?"
        _refuse(script, why)


def _refuse(script, why):
    print(f"{script}: error: {why}", file=sys.stderr)
    sys.exit(2)
