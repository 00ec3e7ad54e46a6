# SPDX-License-Identifier: GPL-3.0-or-later
"""Which file layouts this module reads: the root attribute `schema_version`.

Every HDF5 file shockgas writes (runs, merged runs, checkpoints, analysis results, drift records,
far-tail estimates)
carries `schema_version` next to its provenance (sim/io/include/shockgas/io/provenance.hpp,
`output_schema_version`). The layout of each version is documented in docs/cli-and-output.md.

A new version: add it to SCHEMA_VERSIONS with one line on what changed, and teach the readers in
files.py what differs (each reader is given the file's version). A file of any other version is
refused with UnsupportedSchemaVersion, never read on a guess.
"""

# version -> what it is (one line each; the newest last).
SCHEMA_VERSIONS = {
    1: "the first published layout: fixed-length ASCII text attributes, samples from t > 0",
    2: "the same groups, datasets and attributes, checksummed: HDF5 1.10 file format (metadata "
       "checksums), every non-empty dataset chunked with the Fletcher32 filter",
    3: "text attributes variable-length UTF-8 (h5py gives str); numbered groups (/snapshots, /histograms, "
       "/collapse/states) zero-padded to one width, so they sort in time order; root attributes positions, "
       "velocity_distribution, init_file_sha256",
    4: "the layout of 3; the time series (/timeseries/time and its tables) starts with t = 0, the initial state",
}


class SchemaError(ValueError):
    """The file is not one shockgas wrote, or not the kind the caller asked for."""


class UnsupportedSchemaVersion(SchemaError):
    """The file's schema_version is not one this module reads."""

    def __init__(self, path, version, writer):
        self.path, self.version = path, version
        supported = ", ".join(str(v) for v in sorted(SCHEMA_VERSIONS))
        newest = max(SCHEMA_VERSIONS)
        if isinstance(version, int) and version > newest:
            advice = ("it is newer than this module: read it with the shockgas Python module of the code "
                      "that wrote it (python/shockgas in that source tree), or install a newer shockgas")
        else:
            advice = "read it with the shockgas Python module of the code that wrote it"
        super().__init__(f"{path}: schema_version {version!r} is not one this shockgas module reads "
                         f"({supported}); written by {writer}; {advice}")


def check_schema_version(path, attrs):
    """The file's schema_version (an int), after checking that this module reads it."""
    if "schema_version" not in attrs:
        raise SchemaError(f"{path}: not a file written by shockgas (no schema_version attribute)")
    version = attrs["schema_version"]
    writer = " ".join(str(attrs.get(k, "?")) for k in ("program", "version"))
    try:
        version = int(version)
    except (TypeError, ValueError):
        raise UnsupportedSchemaVersion(path, version, writer) from None
    if version not in SCHEMA_VERSIONS:
        raise UnsupportedSchemaVersion(path, version, writer)
    return version
