# SPDX-License-Identifier: GPL-3.0-or-later
"""Read every file shockgas writes into numpy arrays and attribute dicts (text as str).

    import shockgas
    run = shockgas.read_run("run.h5")
    run.attrs["restitution"], run.attrs["version"]      # parameters and provenance
    run.time, run.temperature                           # K sample times; R x K
    run.temperature.mean(axis=0)                        # the ensemble's T(t)
    for snapshot in run.snapshots:                      # each realization's, in time order
        snapshot.time, snapshot.position, snapshot.velocity, snapshot.mass
    for histogram in run.histograms:
        histogram.time, histogram.edges, histogram.counts
    decay = shockgas.read_results("decay.h5")           # shockgas-analyze output
    decay["decay"].attrs["exponent"], decay.inputs()[0]["seed"]
    tail = shockgas.read_tail("tail.h5")                # shockgas-tail output: tail.z, tail.phi
    shockgas.read("anything.h5")                        # any kind, recognised from the file

The project's scripts refuse a user's mistake in one line "<script>: error: ..." with exit status 2
through shockgas.cli (ArgumentParser, fail).

Every file carries `schema_version`; a version this module does not know is refused with
UnsupportedSchemaVersion, never read on a guess. Layouts: docs/cli-and-output.md; this module:
docs/python.md. It needs numpy and h5py (Debian: python3-numpy, python3-h5py).
"""
from . import cli
from ._h5 import DamagedFile, Group, NoSuchFile, decode, open_file, walk
from .files import (FILE_KINDS, Checkpoint, Drift, File, Results, Run, SpheresCheckpoint, Tail, attributes, file_kind,
                    kind_of, read, read_checkpoint, read_drift, read_initial_condition, read_results, read_run,
                    read_spheres_checkpoint, read_tail, sample_grid, write_initial_condition)
from .schema import SCHEMA_VERSIONS, SchemaError, UnsupportedSchemaVersion, check_schema_version

__all__ = [
    "read", "read_run", "read_checkpoint", "read_spheres_checkpoint", "read_results", "read_drift", "read_tail",
    "attributes", "kind_of", "sample_grid",
    "write_initial_condition", "read_initial_condition", "walk", "open_file", "decode", "DamagedFile", "NoSuchFile",
    "Run", "Checkpoint", "SpheresCheckpoint", "Results", "Drift", "Tail", "File", "Group",
    "SCHEMA_VERSIONS", "SchemaError", "UnsupportedSchemaVersion", "check_schema_version", "FILE_KINDS", "file_kind",
    "cli",
]
