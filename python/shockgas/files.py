"""The kinds of file shockgas writes, and one reader for each (layouts: docs/cli-and-output.md).

    run         shockgas-sim and shockgas-merge output          read_run        -> Run
    checkpoint  a run in progress (OUT.h5.checkpoint)            read_checkpoint -> Checkpoint (a Run)
    results     shockgas-analyze <subcommand> output             read_results    -> Results
    drift       shockgas-drift record                            read_drift      -> Drift
    read(path) recognises the kind itself.

A new kind of file: a class (usually a File subclass), a builder registered with @file_kind that
says how to recognise the file from its root attributes and top-level names, and a public reader:

    class Tail(File): ...
    @file_kind("tail", lambda attrs, names: attrs.get("program") == "shockgas-tail", "read_tail")
    def _tail(path, handle, attrs, version):
        return Tail(read_group(handle), path, version)
    def read_tail(path):
        return read(path, expect="tail")

and its name in __init__.py. Recognisers must not overlap: each file is of one kind.
"""
import h5py
import numpy as np

from ._h5 import Group, decode_attributes, open_file, read_group
from .schema import SchemaError, check_schema_version

# kind -> (recognise(root attributes, top-level names) -> bool,
#          build(path, open h5py file, root attributes, schema version) -> object, public reader's name)
FILE_KINDS = {}


def file_kind(name, recognise, reader_name):
    """Registers the builder of one kind of file (see the module's docstring)."""
    def register(build):
        FILE_KINDS[name] = (recognise, build, reader_name)
        return build
    return register


def kind_of(path):
    """The kind of a shockgas file ("run", "results", ...), after the schema check."""
    with open_file(path) as handle:
        return _kind(path, decode_attributes(handle), set(handle.keys()))


def _kind(path, attrs, names):
    for name, (recognise, _, _) in FILE_KINDS.items():
        if recognise(attrs, names):
            return name
    raise SchemaError(f"{path}: a shockgas file of no kind this module knows (program {attrs.get('program')!r})")


def read(path, expect=None):
    """Reads any shockgas file into the object of its kind; `expect` (a kind name or a tuple of them)
    makes any other kind an error that names the right reader."""
    with open_file(path, check_schema=False) as handle:
        attrs = decode_attributes(handle)
        version = check_schema_version(path, attrs)
        kind = _kind(path, attrs, set(handle.keys()))
        expected = (expect,) if isinstance(expect, str) else expect
        if expect is not None and kind not in expected:
            raise SchemaError(f"{path}: a {kind} file ({attrs.get('program')}), not a {' or '.join(expected)} "
                              f"file: read it with shockgas.{FILE_KINDS[kind][2]} or shockgas.read")
        return FILE_KINDS[kind][1](path, handle, attrs, version)


def attributes(path):
    """The root attributes of a shockgas file (parameters, status, provenance), text as str, without
    reading its datasets."""
    with open_file(path) as handle:
        return decode_attributes(handle)


class File(Group):
    """A whole file read into memory: the root Group, plus `file` (its path) and `schema_version`."""

    def __init__(self, group, path, version):
        super().__init__(group.attrs, group.data, group.groups, "/")
        self.file, self.schema_version = path, version


# ------------------------------------------------------------------------------------------- runs
class Run(File):
    """A shockgas-sim output (or a merged one): attrs (parameters, status, provenance), the time
    series (R realizations x K sample times), snapshots, histograms and collapses.

        run.time                       K sample times
        run.temperature                R x K (NaN where a realization did not reach t), also
        run.kinetic_energy, run.collisions_per_particle, run.clusters, run.realization_status
        run.snapshots                  list of Group: .time .realization .position .velocity .mass .first_particle
        run.histograms                 list of Group: .time .edges (bins+1) .counts (R x (bins+2): under, bins, over)
        run.collapse                   Group (.time .realization .cluster_mass ... .states) or None
    """

    @property
    def timeseries(self):
        return self.groups["timeseries"]

    def __getattr__(self, name):  # run.temperature: the /timeseries dataset
        timeseries = self.__dict__.get("groups", {}).get("timeseries")
        if timeseries is not None and name in timeseries.data:
            return timeseries.data[name]
        return super().__getattr__(name)

    @property
    def realizations(self):
        return int(self.timeseries.data["temperature"].shape[0])

    @property
    def engine_switch_time(self):
        """Per realization, when the hybrid engine handed over to the pass-through engine (inf: not
        yet; NaN: an engine that never switches). NaN for files written before 2026-11-26, which did
        not record it, as the C++ reader gives."""
        recorded = self.timeseries.data.get("engine_switch_time")
        return recorded if recorded is not None else np.full(self.realizations, np.nan)

    @property
    def snapshots(self):
        return list(self.groups["snapshots"].groups.values()) if "snapshots" in self.groups else []

    @property
    def histograms(self):
        return list(self.groups["histograms"].groups.values()) if "histograms" in self.groups else []

    @property
    def collapse(self):
        return self.groups.get("collapse")

    def __repr__(self):
        a = self.attrs
        return (f"<Run {self.file}: N = {a.get('particles')}, r = {a.get('restitution')}, "
                f"delta = {a.get('velocity_threshold')}, {self.realizations} realizations x "
                f"{len(self.timeseries.data['time'])} times, {len(self.snapshots)} snapshots, "
                f"{len(self.histograms)} histograms, status {a.get('status')}>")


def _is_run(attrs, names):
    return "timeseries" in names and "checkpoint" not in names


def _check_run_layout(path, group):
    if "timeseries" not in group.groups or "temperature" not in group.groups["timeseries"].data:
        raise SchemaError(f"{path}: no /timeseries/temperature; not a complete shockgas-sim output")


@file_kind("run", _is_run, "read_run")
def _run(path, handle, attrs, version):
    group = read_group(handle)
    _check_run_layout(path, group)
    return Run(group, path, version)


def read_run(path):
    """A shockgas-sim or shockgas-merge output as a Run (a checkpoint too, as a Checkpoint)."""
    return read(path, expect=("run", "checkpoint"))


class Checkpoint(Run):
    """A run in progress (OUT.h5.checkpoint): the Run done so far (realization_status 4: in
    progress) plus .signature (the run it belongs to), .samples_done (per realization) and .engines
    (realization -> Group with .kind and the engine's state arrays under reals/ and integers/)."""

    @property
    def signature(self):
        return self.groups["checkpoint"].attrs["run_signature"]

    @property
    def samples_done(self):
        return self.groups["checkpoint"].data["samples_done"]

    @property
    def engines(self):
        return {int(name): group for name, group in self.groups["checkpoint"].groups["engines"].groups.items()}


@file_kind("checkpoint", lambda attrs, names: "checkpoint" in names and "timeseries" in names, "read_checkpoint")
def _checkpoint(path, handle, attrs, version):
    group = read_group(handle)
    _check_run_layout(path, group)
    return Checkpoint(group, path, version)


def read_checkpoint(path):
    """A shockgas-sim checkpoint as a Checkpoint."""
    return read(path, expect="checkpoint")


# ---------------------------------------------------------------------------------- analysis results
class Results(File):
    """A shockgas-analyze results file: attrs (the analysis program's provenance, and every root
    attribute of its inputs copied as input_<name>, or input<k>_<name> for several inputs, with
    input_path / input<k>_path), and one group per result (results["decay"].attrs["exponent"])."""

    @property
    def sections(self):
        return self.groups

    def inputs(self):
        """The inputs' root attributes, one dict per input in order (prefix removed)."""
        if "input_path" in self.attrs:
            return [{k[len("input_"):]: v for k, v in self.attrs.items() if k.startswith("input_")}]
        found = []
        k = 0
        while f"input{k}_path" in self.attrs:
            prefix = f"input{k}_"
            found.append({n[len(prefix):]: v for n, v in self.attrs.items() if n.startswith(prefix)})
            k += 1
        return found

    def __repr__(self):
        return f"<Results {self.file} ({self.attrs.get('program')}): {', '.join(self.groups) or 'no sections'}>"


@file_kind("results", lambda attrs, names: str(attrs.get("program", "")).startswith("shockgas-analyze"),
           "read_results")
def _results(path, handle, attrs, version):
    return Results(read_group(handle), path, version)


def read_results(path):
    """A shockgas-analyze results file as Results."""
    return read(path, expect="results")


# ------------------------------------------------------------------------------------------- drift
class Drift(File):
    """A shockgas-drift record: attrs (parameters, provenance) and one column per recorded quantity
    (drift.columns: collisions, time, momentum drift, its rounding bound, ...)."""

    @property
    def columns(self):
        return self.data


@file_kind("drift", lambda attrs, names: attrs.get("program") == "shockgas-drift", "read_drift")
def _drift(path, handle, attrs, version):
    return Drift(read_group(handle), path, version)


def read_drift(path):
    """A shockgas-drift record as Drift."""
    return read(path, expect="drift")


# ------------------------------------------------------------------------------ initial conditions
def write_initial_condition(path, position, velocity, mass=None, ring_length=None):
    """Writes a start for `shockgas-sim --init FILE` (docs/cli-and-output.md): N non-decreasing
    positions in [0, L), N velocities, optional masses (default 1), ring length L (default N)."""
    position, velocity = np.asarray(position, dtype=float), np.asarray(velocity, dtype=float)
    with h5py.File(path, "w") as handle:
        handle.attrs["ring_length"] = float(len(position) if ring_length is None else ring_length)
        handle["position"] = position
        handle["velocity"] = velocity
        if mass is not None:
            handle["mass"] = np.asarray(mass, dtype=float)
