# SPDX-License-Identifier: GPL-3.0-or-later
"""The kinds of file shockgas writes, and one reader for each (layouts: docs/cli-and-output.md).

    run         shockgas-sim and shockgas-merge output          read_run        -> Run
    checkpoint  a run in progress (OUT.h5.checkpoint)            read_checkpoint -> Checkpoint (a Run)
    spheres_checkpoint  a shockgas-spheres run in progress       read_spheres_checkpoint -> SpheresCheckpoint
    results     shockgas-analyze <subcommand> output             read_results    -> Results
    drift       shockgas-drift record                            read_drift      -> Drift
    tail        shockgas-tail far-tail estimate of Phi           read_tail       -> Tail
    read(path) recognises the kind itself.

A new kind of file: a class (usually a File subclass), a builder registered with @file_kind that
says how to recognise the file from its root attributes and top-level names, and a public reader
(the tail kind below is one):

    class Tail(File): ...
    @file_kind("tail", lambda attrs, names: attrs.get("program") == "shockgas-tail", "read_tail")
    def _tail(path, handle, attrs, version):
        return Tail(read_group(handle), path, version)
    def read_tail(path):
        return read(path, expect="tail")

and its name in __init__.py. Recognisers must not overlap: each file is of one kind.
"""
import errno
import os

import h5py
import numpy as np

from ._h5 import Group, decode, decode_attributes, open_file, read_dataset, read_group
from .cli import atomic_output_path
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
        yet; NaN: an engine that never switches). NaN for files of older versions, which did not
        record it, as the C++ reader gives."""
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
        return (f"<{type(self).__name__} {self.file}: N = {a.get('particles')}, r = {a.get('restitution')}, "
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


class SpheresCheckpoint(File):
    """A shockgas-spheres run in progress (OUT.h5.checkpoint): attrs (parameters, cpu_seconds,
    provenance) and, per realization begun, its progress; the realizations' arrays are not read
    (they can take gigabytes), only their attributes:

        checkpoint.progress        {realization: (samples_done, finished)}
        checkpoint.time            the run's sample times (sample_grid, below)
    """

    def __init__(self, path, version, attrs, progress):
        super().__init__(Group(attrs, {}, {}, "/"), path, version)
        self.progress = progress

    @property
    def time(self):
        return sample_grid(self.attrs)


def sample_grid(attrs):
    """The sample times of a shockgas-spheres run from its attributes, as the program computes them
    (sim/spheres/src/parameters.cpp, sample_grid): t = 0, then t = 10^(-2 + k/K) up to t_max, then
    t_max, with every listed sample, snapshot and histogram time up to t_max, sorted, without repeats."""
    t_max, per_decade = float(attrs["t_max"]), int(attrs["samples_per_decade"])
    last = np.log10(t_max)
    grid = {0.0, t_max}
    k = 0
    while -2.0 + k / per_decade <= last + 1e-12:
        grid.add(10.0 ** (-2.0 + k / per_decade))
        k += 1
    for name in ("sample_times", "snapshot_times", "histogram_times"):
        grid.update(float(t) for t in np.atleast_1d(attrs.get(name, [])) if t <= t_max)
    return np.array(sorted(grid))


@file_kind("spheres_checkpoint", lambda attrs, names: attrs.get("schema") == "spheres-checkpoint",
           "read_spheres_checkpoint")
def _spheres_checkpoint(path, handle, attrs, version):
    progress = {}
    for name, group in handle.get("realizations", {}).items():
        done = decode_attributes(group)
        progress[int(name)] = (int(done["samples_done"]), bool(done["finished"]))
    return SpheresCheckpoint(path, version, attrs, progress)


def read_spheres_checkpoint(path):
    """A shockgas-spheres checkpoint as SpheresCheckpoint."""
    return read(path, expect="spheres_checkpoint")


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


# ------------------------------------------------------------------------------------------- tail
class Tail(File):
    """A shockgas-tail output: the far tail of the scaled velocity law Phi(z) at one time by the
    large-deviation sampler (docs/far-tail.md). attrs: every parameter (time, half_window, chains,
    steps_per_bias, velocity_law, seed, ...), evaluations, provenance. Datasets, one value per z bin:

        tail.z, tail.phi, tail.phi_sigma, tail.log_phi, tail.log_phi_sigma, tail.samples
        tail.log_phi_leave_one_chain_out      chains x bins (the jackknife's replicas)
        tail.pieces                           Group, one value per bias: .bias .acceptance .mean_z
                                              .log_partition .overlap_with_next .swap_acceptance
    """

    @property
    def pieces(self):
        return self.groups.get("pieces")

    def __repr__(self):
        a = self.attrs
        return (f"<Tail {self.file}: t = {a.get('time')}, {len(self.data['z'])} bins of z in "
                f"[{a.get('z_min')}, {a.get('z_max')}], {a.get('chains')} chains x {a.get('steps_per_bias')} steps "
                f"per bias, {len(self.pieces.data.get('bias', [])) if self.pieces else 0} biases>")


@file_kind("tail", lambda attrs, names: attrs.get("program") == "shockgas-tail", "read_tail")
def _tail(path, handle, attrs, version):
    group = read_group(handle)
    for name in ("z", "phi", "log_phi"):
        if name not in group.data:
            raise SchemaError(f"{path}: no /{name}; not a complete shockgas-tail output")
    return Tail(group, path, version)


def read_tail(path):
    """A shockgas-tail far-tail estimate as Tail."""
    return read(path, expect="tail")


# ------------------------------------------------------------------------------ initial conditions
def _check_initial_condition(position, velocity, mass, ring_length):
    """The checks shockgas-sim's init reader makes (sim/model/src/state.cpp, validate), as ValueError."""
    if position.ndim != 1 or velocity.ndim != 1 or (mass is not None and mass.ndim != 1):
        raise ValueError("init: position, velocity and mass must be one-dimensional")
    n = len(position)
    if not (ring_length > 0.0 and np.isfinite(ring_length)):
        raise ValueError(f"init: ring_length must be positive and finite, got {ring_length}")
    if n < 2:
        raise ValueError(f"init: need at least 2 particles, got {n}")
    if len(velocity) != n:
        raise ValueError(f"init: velocity has {len(velocity)} values but position has {n}")
    if mass is not None and len(mass) != n:
        raise ValueError(f"init: mass has {len(mass)} values but position has {n}")
    for name, values in (("position", position), ("velocity", velocity)):
        bad = np.flatnonzero(~np.isfinite(values))
        if bad.size:
            raise ValueError(f"init: {name}[{bad[0]}] is not finite")
    if mass is not None:
        bad = np.flatnonzero(~(np.isfinite(mass) & (mass > 0.0)))
        if bad.size:
            raise ValueError(f"init: mass[{bad[0]}] must be positive and finite, got {mass[bad[0]]}")
    bad = np.flatnonzero((position < 0.0) | (position >= ring_length))
    if bad.size:
        raise ValueError(f"init: position[{bad[0]}] = {position[bad[0]]} lies outside [0, ring_length = {ring_length})")
    bad = np.flatnonzero(position[1:] < position[:-1])
    if bad.size:
        i = bad[0] + 1
        raise ValueError(f"init: positions are not sorted: position[{i}] = {position[i]} < "
                         f"position[{i - 1}] = {position[i - 1]}")


def _refuse_to_replace(path, overwrite):
    """Raises FileExistsError unless writing `path` may replace what is there: nothing, or, with
    overwrite=True, a regular file that is not one shockgas wrote (a run, results, ...)."""
    if not os.path.lexists(path):
        return
    if os.path.islink(path) or not os.path.isfile(path):
        raise FileExistsError(errno.EEXIST, "exists and is not a regular file (a directory, device, FIFO or "
                                            "symbolic link); an initial condition is never written over it", path)
    attrs = None
    try:
        if h5py.is_hdf5(path):
            with open_file(path, check_schema=False) as handle:
                attrs = decode_attributes(handle)
    except PermissionError:
        raise FileExistsError(errno.EEXIST, "exists and cannot be read to tell whether shockgas wrote it; "
                                            "not replaced", path) from None
    except OSError:  # damaged HDF5: not readable as a shockgas file either
        attrs = None
    if attrs is not None and ("schema_version" in attrs or "program" in attrs):
        raise FileExistsError(errno.EEXIST, f"is a shockgas file ({attrs.get('program', 'shockgas')} output); "
                                            f"an initial condition is never written over one", path)
    if not overwrite:
        raise FileExistsError(errno.EEXIST, "exists; pass overwrite=True to replace it", path)


# Values per chunk of a dataset, at most: sim/io/src/h5.cpp's max_chunk_elements (8 MiB of doubles).
_MAX_CHUNK_VALUES = 1 << 20


def write_initial_condition(path, position, velocity, mass=None, ring_length=None, overwrite=False):
    """Writes a start for `shockgas-sim --init FILE` (docs/cli-and-output.md): N >= 2 non-decreasing
    finite positions in [0, L), N finite velocities, optional masses (> 0, default 1), ring length L
    (> 0, default N). Checked as shockgas-sim checks it (ValueError naming the first bad value).

    An existing file is refused (FileExistsError) unless overwrite=True; a file shockgas wrote (a run,
    checkpoint, results, ...) and anything that is not a regular file are never replaced. The file is
    written beside its destination under a temporary name and renamed into place: an error leaves
    no partial file and the old one, if any, untouched."""
    position, velocity = np.asarray(position, dtype=float), np.asarray(velocity, dtype=float)
    mass = None if mass is None else np.asarray(mass, dtype=float)
    ring_length = float(len(position) if ring_length is None else ring_length)
    _check_initial_condition(position, velocity, mass, ring_length)
    path = os.fspath(path)
    _refuse_to_replace(path, overwrite)
    directory = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(directory):
        raise FileNotFoundError(errno.ENOENT, f"no directory {directory} to write it in", path)
    with atomic_output_path(path, replace=overwrite) as temporary:  # never replaces when not asked
        # As shockgas-sim writes every file (sim/io/src/h5.cpp): the HDF5 1.10 format, whose metadata carry
        # checksums, and each dataset chunked (at most 2^20 values a chunk) with the Fletcher32 checksum,
        # which HDF5 checks whenever the data are read; no object times, so the same start gives the
        # same bytes.
        with h5py.File(temporary, "w", libver=("v110", "v110")) as handle:
            handle.attrs["ring_length"] = ring_length
            for name, values in (("position", position), ("velocity", velocity), ("mass", mass)):
                if values is not None:
                    handle.create_dataset(name, data=values, chunks=(min(len(values), _MAX_CHUNK_VALUES),),
                                          fletcher32=True, track_times=False)
        _refuse_to_replace(path, overwrite)  # again: something may have appeared meanwhile


def _describe(value):
    """An attribute's value in a message: a string as such, else its type."""
    if value.dtype.kind in "SUO":
        text = decode(value[()] if value.shape == () else value.reshape(-1)[0]) if value.size else ""
        return f"a string ({str(text)[:40]!r})" if value.size == 1 else f"{value.size} strings"
    return f"of type {value.dtype}"


def _initial_item(handle, name):
    """The one-dimensional numeric dataset `name` of a start as a float array, else ValueError saying why."""
    item = handle.get(name)
    if not isinstance(item, h5py.Dataset):
        what = "a group" if isinstance(item, h5py.Group) else f"a {type(item).__name__}"
        raise ValueError(f"{name} is {what}, not a dataset; it must be a one-dimensional dataset of N numbers")
    if item.shape is None or len(item.shape) != 1:
        shape = "empty (no dataspace)" if item.shape is None else f"of shape {item.shape}"
        raise ValueError(f"{name} is a dataset {shape}; it must be one-dimensional (N numbers)")
    if item.dtype.kind not in "iuf":
        raise ValueError(f"{name} holds {item.dtype} values, not numbers")
    return np.asarray(read_dataset(handle.file.filename, item), dtype=float)  # a failed checksum: DamagedFile


def read_initial_condition(path):
    """(position, velocity, mass or None, ring_length) of a start written for `shockgas-sim --init`
    (write_initial_condition's format: datasets position, velocity, optional mass, attribute
    ring_length), as float arrays and a float; checked as write_initial_condition checks what it
    writes (ValueError naming the first bad value). A malformed file is a ValueError too, saying what
    is wrong: position, velocity or mass not a one-dimensional numeric dataset (a group, a 2-D or
    scalar dataset, strings), ring_length not a single number (an array, a string)."""
    with open_file(path, check_schema=False) as handle:
        missing = [name for name in ("position", "velocity") if name not in handle]
        if "ring_length" not in handle.attrs:
            missing.append("ring_length")
        if missing:
            raise ValueError(f"not an initial condition for shockgas-sim --init (no {', '.join(missing)}; it needs "
                             f"the datasets position and velocity and the root attribute ring_length)")
        try:
            position = _initial_item(handle, "position")
            velocity = _initial_item(handle, "velocity")
            mass = _initial_item(handle, "mass") if "mass" in handle else None
        except ValueError as error:
            raise ValueError(f"not an initial condition for shockgas-sim --init: {error}") from None
        try:
            value = np.asarray(handle.attrs["ring_length"])
        except (OSError, TypeError, ValueError) as error:  # a type h5py cannot read
            raise ValueError(f"not an initial condition for shockgas-sim --init: the root attribute ring_length "
                             f"cannot be read ({error}); it must be a single number") from None
        if value.dtype.kind not in "iuf":
            raise ValueError(f"not an initial condition for shockgas-sim --init: the root attribute ring_length is "
                             f"{_describe(value)}, not a number; it must be a single number (the ring length L)")
        if value.size != 1:
            raise ValueError(f"not an initial condition for shockgas-sim --init: the root attribute ring_length holds "
                             f"{value.size} values (shape {value.shape}); it must be a single number (the ring "
                             f"length L)")
        ring_length = float(value.reshape(()))
    _check_initial_condition(position, velocity, mass, ring_length)
    return position, velocity, mass, ring_length
