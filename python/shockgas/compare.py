# SPDX-License-Identifier: GPL-3.0-or-later
"""Comparing two outputs of shockgas: which attributes describe a run rather than its results, and
the rules by which a file and its rerun are the same.

    from shockgas import compare
    problems, datasets = compare.identical_runs("reference.h5", "resumed.h5")   # bit for bit
    exact, differences, note = compare.compare_h5(archived, rerun, archived_paths, rerun_paths, 3.0)

RUN_DEPENDENT_ATTRIBUTES is the one list of root attributes in which two runs of the same code and
parameters differ (when, where and how fast they ran): identical_runs (tests/compare_outputs.py, the
checkpoint and MPI tests) leaves them out, and so does the archive check (shockgas.archive,
tools/reproduce-check, docs/archive.md), which also leaves out the provenance attributes, maps build
paths, and compares within sigma across toolchains.
"""
import hashlib
import json
import math
import re

import numpy as np

from ._h5 import decode, walk

# Root attributes that legitimately differ between two runs of the same code and
# compiler: when and where a run was made and how long it took (wall/CPU time and
# peak memory depend on the machine's load). An archive records them in MANIFEST
# but they are never compared. Analysis results copy them forward as input_<name> / input<k>_<name>.
# A merged run's merged_date (shockgas-merge) is when the merge ran.
RUN_DEPENDENT_ATTRIBUTES = {"date", "host", "wall_seconds", "cpu_seconds", "start_cpu_seconds", "peak_memory_bytes",
                            "merged_date"}
# The code and toolchain that made a file. Compared separately: a difference is
# reported (code version) or selects the tolerant comparison (compiler, flags,
# build type, HDF5 library), it is not itself a data difference. simulator_sha256
# (the SHA-256 of the simulator's sources, compiler and flags, absent from files of older builds;
# analysis results copy it as input_simulator_sha256) says which simulator made a
# file: two files that both have it are of the same simulator when it is the same,
# whatever their `version` (sim/io/src/provenance.cpp same_simulator).
TOOLCHAIN_ATTRIBUTES = ("compiler", "compiler_flags", "build_type", "hdf5_version")
PROVENANCE_ATTRIBUTES = {"program", "version", "simulator_sha256", "merged_by", *TOOLCHAIN_ATTRIBUTES}
INPUT_PREFIX = re.compile(r"^input\d*_")
# shockgas-dump gnuplot-vars writes every root attribute as <prefix>_<name> = value, the volatile
# and provenance ones included (fig5's shocks.gp, fig_tradeoff's reference.gp and *.fit.gp): those
# lines are not compared, as the attributes themselves are not. (A name ending in one of these,
# such as schema_version, is left out too; the HDF5 file it came from is compared in full.)
GP_VOLATILE = re.compile(rb"^\w*_(" + "|".join(sorted(RUN_DEPENDENT_ATTRIBUTES | PROVENANCE_ATTRIBUTES)).encode()
                         + rb") = .*\n", re.M)
# Cross-toolchain tolerance: |a - b| <= k sqrt(sigma_a^2 + sigma_b^2). Roundoff
# differences grow exponentially in a many-body collision sequence, so after a
# long run the two ensembles are, at worst, independent draws with the same
# seeds' statistics; their difference then has standard deviation
# sqrt(sigma_a^2 + sigma_b^2), and k = 3 gives 0.3 % false alarms per number.
DEFAULT_SIGMA_FACTOR = 3.0
PDF_VOLATILE = re.compile(rb"^\s*/(CreationDate|ModDate) \(D:[^)]*\)\s*$", re.M)
# A merged run's merged_from names each part's code version ("<path> (realizations 0 to 9, shockgas
# <version>)"): parts of one simulator made at other commits (kept by the pipeline's stamp) are the
# same data, so the versions are provenance, not content.
MERGED_FROM_VERSION = re.compile(r", shockgas [^)\n]*\)")
# The date line of a text output's provenance (shockgas::provenance_comment: shockgas-burgers'
# profile and --summary): when it was written, the one line in which a rerun differs.
TEXT_VOLATILE = re.compile(rb"^# date \S+\n", re.M)
# The program-and-version line of the same comment ("# shockgas-analyze <version>, from ..."): the
# version is provenance, as the HDF5 files' `version` attribute is (a file made at an earlier commit
# of the same code is the same data); the program and the inputs are compared.
TEXT_VERSION = re.compile(rb"^(# shockgas-[a-z]+) \S+?(,|\n)", re.M)


def base_attribute(name):
    return INPUT_PREFIX.sub("", name)


class PathNormalizer:
    """Absolute build/source paths appear in attributes (input_path) and .dat headers;
    a rerun in another directory writes other paths, so both sides are mapped to
    <BUILD> and <SOURCE> before comparing."""

    def __init__(self, build_dir, source_dir):
        self.pairs = [(p.rstrip("/"), tag) for p, tag in ((build_dir, "<BUILD>"), (source_dir, "<SOURCE>")) if p]
        self.pairs.sort(key=lambda pair: -len(pair[0]))

    def text(self, value):
        for path, tag in self.pairs:
            value = value.replace(path, tag)
        return value

    def data(self, raw):
        for path, tag in self.pairs:
            raw = raw.replace(path.encode(), tag.encode())
        return raw


# ------------------------------------------------------- HDF5 canonical walk
def h5_walk(path, normalizer):
    """{object path: {"attrs": {name: value}, "dataset": (dtype, shape, bytes) or None}}"""
    objects = {}
    for name, attributes, data in walk(path):
        attributes = {k: normalizer.text(v) if isinstance(v, str) else v for k, v in attributes.items()}
        for attribute, value in attributes.items():
            if base_attribute(attribute) == "merged_from" and isinstance(value, str):
                attributes[attribute] = MERGED_FROM_VERSION.sub(")", value)
        entry = {"attrs": attributes, "dataset": None}
        if data is not None:
            array = np.ascontiguousarray(data)
            if array.dtype.kind in "SO":
                raw = json.dumps(decode(array) if array.shape else decode(data)).encode()
            else:
                raw = array.tobytes()
            entry["dataset"] = (str(array.dtype), tuple(array.shape), raw)
        objects[name] = entry
    return objects


def value_bytes(value):
    if isinstance(value, (str, list)):
        return json.dumps(value).encode()
    array = np.asarray(value)
    return array.dtype.str.encode() + b":" + array.tobytes()


def content_digest(objects):
    """SHA-256 over every dataset and every attribute except the volatile and
    provenance ones: identical for two runs of the same code and compiler."""
    digest = hashlib.sha256()
    for path in sorted(objects):
        entry = objects[path]
        digest.update(path.encode() + b"\0")
        for name in sorted(entry["attrs"]):
            if base_attribute(name) in RUN_DEPENDENT_ATTRIBUTES | PROVENANCE_ATTRIBUTES:
                continue
            digest.update(name.encode() + b"=" + value_bytes(entry["attrs"][name]) + b"\0")
        if entry["dataset"] is not None:
            dtype, shape, raw = entry["dataset"]
            digest.update(f"{dtype}{shape}".encode() + hashlib.sha256(raw).digest())
    return digest.hexdigest()


def format_number(value):
    return repr(value.item() if isinstance(value, np.generic) else value)


def compare_h5(archived, rerun, archived_norm, rerun_norm, sigma_factor):
    """Returns (exact_mode, differences, version_note)."""
    a, b = h5_walk(archived, archived_norm), h5_walk(rerun, rerun_norm)
    root_a, root_b = a["/"]["attrs"], b["/"]["attrs"]
    exact = all(root_a.get(k) == root_b.get(k) for k in TOOLCHAIN_ATTRIBUTES)
    for name in root_a:  # analysis results: the inputs' toolchain too
        if base_attribute(name) in TOOLCHAIN_ATTRIBUTES and root_a.get(name) != root_b.get(name):
            exact = False
    version_note = None
    if root_a.get("version") != root_b.get("version"):
        version_note = f"made by {root_a.get('version')}, rerun by {root_b.get('version')}"
        if same_simulator(root_a, root_b) == "same simulator":
            version_note += ", the same simulator (simulator_sha256)"
    differences = []
    for path in sorted(set(a) | set(b)):
        if path not in b:
            differences.append(f"{path} missing in rerun")
            continue
        if path not in a:
            differences.append(f"{path} only in rerun")
            continue
        attrs_a, attrs_b = a[path]["attrs"], b[path]["attrs"]
        for name in sorted(set(attrs_a) | set(attrs_b)):
            base = base_attribute(name)
            if base in RUN_DEPENDENT_ATTRIBUTES or base in PROVENANCE_ATTRIBUTES:
                continue
            if name not in attrs_a or name not in attrs_b:
                differences.append(f"{path} attribute {name} only in {'rerun' if name in attrs_b else 'archive'}")
                continue
            va, vb = attrs_a[name], attrs_b[name]
            if exact:
                if value_bytes(va) != value_bytes(vb):
                    differences.append(f"{path} attribute {name}: archive {format_number(va)}, rerun {format_number(vb)}")
            elif name + "_sigma" in attrs_a and name + "_sigma" in attrs_b:
                try:
                    xa, xb = float(va), float(vb)
                    sa, sb = float(attrs_a[name + "_sigma"]), float(attrs_b[name + "_sigma"])
                except (TypeError, ValueError):
                    continue
                allowed = sigma_factor * math.hypot(sa, sb)
                if not (abs(xa - xb) <= allowed or (math.isnan(xa) and math.isnan(xb))):
                    differences.append(f"{path} {name}: archive {xa!r} ± {sa:.3g}, rerun {xb!r} ± {sb:.3g}: "
                                       f"|Δ| = {abs(xa - xb):.3g} > {sigma_factor:g}·√(σa²+σb²) = {allowed:.3g}")
        if exact and (a[path]["dataset"] is not None or b[path]["dataset"] is not None):
            da, db = a[path]["dataset"], b[path]["dataset"]
            if da is None or db is None:
                differences.append(f"{path}: dataset on one side only")
            elif da[:2] != db[:2]:
                differences.append(f"dataset {path}: {da[0]}{list(da[1])} vs {db[0]}{list(db[1])}")
            elif da[2] != db[2]:
                why = f"dataset {path} differs"
                if da[0].startswith(("float", "int", "uint")):
                    xa = np.frombuffer(da[2], dtype=da[0])
                    xb = np.frombuffer(db[2], dtype=db[0])
                    unequal = xa != xb
                    if xa.dtype.kind == "f":
                        unequal &= ~(np.isnan(xa) & np.isnan(xb))
                    unequal = np.flatnonzero(unequal)
                    if unequal.size:
                        i = unequal[0]
                        why += (f": {unequal.size} of {xa.size} elements, first at flat index {i}: "
                                f"archive {xa[i]!r}, rerun {xb[i]!r}")
                differences.append(why)
    return exact, differences, version_note


def without_volatile_columns(text):
    """A data file (DataFile: "# <title>", "# <program and inputs>", "# <column names>", rows) with the
    columns named after a volatile attribute (fig_tradeoff's tradeoff.dat: cpu_seconds) blanked in
    every row: what a run cost is recorded, not compared, as in the HDF5 files."""
    lines = text.split(b"\n")
    names = next((line[1:].split() for line in lines[:4] if line.startswith(b"#")
                  and any(n.decode(errors="replace") in RUN_DEPENDENT_ATTRIBUTES for n in line[1:].split())), None)
    if names is None:
        return text
    volatile = {i for i, n in enumerate(names) if n.decode(errors="replace") in RUN_DEPENDENT_ATTRIBUTES}
    rows = []
    for line in lines:
        fields = line.split()
        if line.startswith(b"#") or len(fields) != len(names):
            rows.append(line)
        else:
            rows.append(b" ".join(b"-" if i in volatile else f for i, f in enumerate(fields)))
    return b"\n".join(rows)


def compare_bytes(archived, rerun, category, archived_norm, rerun_norm):
    with open(archived, "rb") as handle:
        a = handle.read()
    with open(rerun, "rb") as handle:
        b = handle.read()
    if category in ("data", "theory"):
        a, b = archived_norm.data(a), rerun_norm.data(b)
    if archived.endswith(".pdf"):
        a, b = PDF_VOLATILE.sub(b"", a), PDF_VOLATILE.sub(b"", b)
    if archived.endswith((".dat", ".gp")):
        a, b = TEXT_VOLATILE.sub(b"", a), TEXT_VOLATILE.sub(b"", b)
        a, b = TEXT_VERSION.sub(rb"\1 <VERSION>\2", a), TEXT_VERSION.sub(rb"\1 <VERSION>\2", b)
    if archived.endswith(".gp"):
        a, b = GP_VOLATILE.sub(b"", a), GP_VOLATILE.sub(b"", b)
    if archived.endswith(".dat"):
        a, b = without_volatile_columns(a), without_volatile_columns(b)
    if a == b:
        return None
    if archived.endswith((".dat", ".gp", ".json")):
        la, lb = a.decode(errors="replace").splitlines(), b.decode(errors="replace").splitlines()
        for i, (x, y) in enumerate(zip(la, lb)):
            if x != y:
                return f"line {i + 1}: archive '{x[:80]}', rerun '{y[:80]}'"
        return f"{len(la)} lines in archive, {len(lb)} in rerun"
    return f"{len(a)} bytes in archive, {len(b)} in rerun, contents differ"


def same_simulator(archived, compared):
    """Whether two files' root attributes (dicts) name the same code, as shockgas-sim decides it
    (sim/io/src/provenance.cpp same_simulator): "same simulator" when both have the same simulator_sha256,
    "different simulator" when both have one and they differ, else None: the `version`s decide. Two
    hashes that differ where the compiler, flags or build type differ too (--cxx, another build) may
    differ by the toolchain alone, which selects the tolerant comparison and is no code difference:
    None then, too."""
    a, b = archived.get("simulator_sha256"), compared.get("simulator_sha256")
    if not a or not b:
        return None
    if str(a) == str(b):
        return "same simulator"
    if any(archived.get(k) != compared.get(k) for k in ("compiler", "compiler_flags", "build_type")):
        return None
    return "different simulator"


# Written only by a run with more than one MPI rank.
DISTRIBUTED_ONLY = {"mpi_ranks"}


def same_value(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def identical_runs(reference, other, ranks=None):
    """Whether two shockgas-sim files are identical bit for bit, every group, dataset and attribute,
    except the root attributes that describe the run rather than its results (RUN_DEPENDENT_ATTRIBUTES;
    mpi_ranks in `other` alone). Bitwise, not within a tolerance: for a one-process run against an MPI
    run (ranks: the rank count `other` must record) or an uninterrupted run against a killed and
    resumed one, both files come from the same seed streams through the same arithmetic, so any
    difference is a bug. Returns (problems, one line each; the number of datasets compared)."""
    problems = []
    single, distributed = _objects(reference), _objects(other)
    if list(single) != list(distributed):
        problems.append(f"objects differ: {sorted(set(single) ^ set(distributed))}")
    datasets = 0
    for name, (attrs_a, value_a) in single.items():
        if name not in distributed:
            continue
        attrs_b, value_b = distributed[name]
        if value_a is not None:
            datasets += 1
            if not same_value(value_a, value_b):
                problems.append(f"dataset {name} differs")
        skip = RUN_DEPENDENT_ATTRIBUTES if name == "/" else set()
        extra = DISTRIBUTED_ONLY if name == "/" else set()
        keys_a = set(attrs_a) - skip
        keys_b = set(attrs_b) - skip - extra
        if keys_a != keys_b:
            problems.append(f"attributes of {name} differ in names: {sorted(keys_a ^ keys_b)}")
        for key in sorted(keys_a & keys_b):
            if not same_value(attrs_a[key], attrs_b[key]):
                problems.append(f"attribute {key} of {name} differs: {attrs_a[key]!r} vs {attrs_b[key]!r}")
    if ranks is not None:
        recorded = distributed["/"][0].get("mpi_ranks")
        if recorded != ranks:
            problems.append(f"mpi_ranks is {recorded!r}, expected {ranks}")
    if datasets == 0:
        problems.append("no datasets compared")
    return problems, datasets


def _objects(path):
    """{object path: (attributes as stored, dataset value or None)}, in the file's order."""
    return {name: (attrs, value) for name, attrs, value in walk(path, raw=True)}
