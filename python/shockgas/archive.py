# SPDX-License-Identifier: GPL-3.0-or-later
"""Archiving a shockgas figure build, and checking that an archive reproduces: the work of
tools/reproduce-check, its command line (main) included (docs/archive.md).

    from shockgas import archive
    archive.main(["pack", "--build-dir", "build", "--source-dir", ".", "--fidelity", "quick", "--figures", "fig3"])
    archive.main(["build/shockgas-v1-quick-fig3.tar.gz", "--compare-with", "build"])   # the exit status

pack writes the archive: parameters, results, figures, raw runs (or their hashes), MANIFEST and the
source; check unpacks one, verifies it against MANIFEST, rebuilds it (or takes an existing build) and
compares file by file with the rules of shockgas.compare. Needs numpy and h5py, and git, CMake and
the build's dependencies for a rebuild.
"""
import argparse
import datetime
import glob
import hashlib
import json
import os
import re
import shutil
import socket
import subprocess
import sys
import tarfile
import tempfile

import h5py
import numpy as np

from ._h5 import DamagedFile
from .cli import ArgumentParser, cannot_write, check_output_directory, fail
from .compare import (DEFAULT_SIGMA_FACTOR, RUN_DEPENDENT_ATTRIBUTES, TOOLCHAIN_ATTRIBUTES, PathNormalizer,
                      compare_bytes, compare_h5, content_digest, h5_walk, same_simulator)
from .files import attributes

# tools/reproduce-check --help.
USAGE = """Archive a shockgas figure build, and check that an archive reproduces.

  tools/reproduce-check ARCHIVE.tar.gz [--work-dir DIR] [--source DIR] [--compare-with BUILD]
      Unpack ARCHIVE, verify every file against its SHA-256 in MANIFEST, rebuild the
      source recorded in the archive (git bundle + working-tree snapshot) in a fresh
      build directory, rerun the archived figures and compare file by file.
  tools/reproduce-check pack --build-dir BUILD --source-dir SRC --fidelity F --figures fig1;fig3 ...
      Write shockgas-<git describe>-<fidelity>.tar.gz (what `cmake --build build --target
      archive` runs).

docs/archive.md describes the archive layout, the comparison rules and the exit status.
Uses only the standard library, numpy and h5py (Debian: python3-h5py, run with /usr/bin/python3).
"""

MANIFEST_FORMAT = 1
DEFAULT_MAX_RAW_MB = 50.0
# Figures that plot what a run cost (CPU seconds): their PNG and PDF differ from machine to machine
# and from run to run, so they are listed, with this reason, but not compared. Their numbers are
# compared in the data files, with the cost columns left out (shockgas.compare.without_volatile_columns).
FIGURES_PLOTTING_COSTS = {"fig_tradeoff": "it plots CPU seconds, which depend on the machine and its load"}


# ---------------------------------------------------------------- utilities
def sha256_file(path):
    digest = hashlib.sha256()
    with open(path, "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def run(command, cwd=None, capture=True, check=True):
    result = subprocess.run(command, cwd=cwd, text=True, stdout=subprocess.PIPE if capture else None,
                            stderr=subprocess.PIPE if capture else None)
    if check and result.returncode != 0:
        detail = (result.stderr or "").strip()[-2000:] if capture else ""
        raise RuntimeError(f"command failed ({result.returncode}): {' '.join(command)}\n{detail}")
    return (result.stdout or "").strip() if capture else ""


def tool_version(command, pattern=r"[\d][\w.\-]*"):
    try:
        text = run(command, check=False)
    except OSError:
        return "not found"
    match = re.search(pattern, text)
    return match.group(0) if match else (text.splitlines()[0] if text else "unknown")


def environment_versions():
    return {
        "gnuplot": tool_version(["gnuplot", "--version"]),
        "gsl (gsl-config)": tool_version(["gsl-config", "--version"]),
        "cmake": tool_version(["cmake", "--version"]),
        "python": sys.version.split()[0],
        "numpy": np.__version__,
        "h5py": h5py.__version__,
        "hdf5 (h5py)": h5py.version.hdf5_version,
        "platform": " ".join(os.uname()[i] for i in (0, 2, 4)),
    }


def git_describe(source_dir):
    try:
        return run(["git", "describe", "--always", "--dirty", "--tags"], cwd=source_dir)
    except (RuntimeError, OSError):
        return "unknown (not a git checkout)"


def provenance(objects):
    root = objects["/"]["attrs"]
    keys = ["program", "version", "simulator_sha256", *TOOLCHAIN_ATTRIBUTES, "host", "date", "seed", "engine", "status",
            "wall_seconds", "cpu_seconds", "peak_memory_bytes", "schema_version"]
    return {k: (v.item() if isinstance(v, np.generic) else v) for k in keys if (v := root.get(k)) is not None}


# ------------------------------------------------------------------- packing
def figure_runs(parameter_file):
    with open(parameter_file) as handle:
        spec = json.load(handle)
    return spec.get("runs", [])


def run_command(run_spec, output):
    options = dict(run_spec["options"])
    realizations = options.pop("realizations", 1)
    args = ["shockgas-sim"]
    for key, value in options.items():
        args += [f"--{key}", str(value)]
    args += ["--realizations", str(realizations), "--output", output]
    parts = run_spec.get("parts", 1)
    text = " ".join(args)
    if parts > 1:
        text += (f"   (built as {parts} parts with --first-realization and joined by shockgas-merge;"
                 " the merged file's datasets are identical)")
    return text


def classify(relative, raw_names):
    name = os.path.basename(relative)
    if relative.startswith("figures/"):
        return "figure"
    if relative.startswith("paper_targets/theory/"):
        return "theory"
    if name.endswith(".h5"):
        return "raw" if name[:-3] in raw_names else "result"
    return "data"


def pack(args):
    # The archive's folder is refused now if it cannot be made or written in, not after the packing.
    check_output_directory(args.output_dir or args.build_dir, "--output-dir" if args.output_dir else "--build-dir",
                           "reproduce-check pack")
    build_dir = os.path.realpath(args.build_dir)
    source_dir = os.path.realpath(args.source_dir)
    figures = [f for f in re.split(r"[;,\s]+", args.figures) if f]
    fidelity = args.fidelity
    version = git_describe(source_dir)
    max_raw = args.max_raw_mb * 1e6
    name = f"shockgas-{version}-{fidelity}{args.suffix}"
    output = os.path.join(args.output_dir or build_dir, name + ".tar.gz")
    normalizer = PathNormalizer(build_dir, source_dir)
    stage = tempfile.mkdtemp(prefix="shockgas-pack-")
    try:
        return pack_in(args, stage, name, build_dir, source_dir, figures, fidelity, version, max_raw, output,
                       normalizer)
    finally:  # on every way out, a missing file included
        shutil.rmtree(stage, ignore_errors=True)


def pack_in(args, stage, name, build_dir, source_dir, figures, fidelity, version, max_raw, output, normalizer):
    root = os.path.join(stage, name)
    os.makedirs(root)
    files, runs = [], []

    def add(relative_in_archive, source_path, category, figure, command, archived=True, extra=None):
        entry = {"path": relative_in_archive, "category": category, "figure": figure,
                 "size": os.path.getsize(source_path), "sha256": sha256_file(source_path),
                 "archived": archived, "regenerate": command}
        if extra:
            entry.update(extra)
        if archived:
            target = os.path.join(root, relative_in_archive)
            os.makedirs(os.path.dirname(target), exist_ok=True)
            shutil.copy2(source_path, target)
        files.append(entry)
        return entry

    figure_command = "cmake --build <BUILD> --target {0}   (rule in paper_targets/{0}.cmake)"
    theory_seen = set()
    for figure in figures:
        parameter_file = os.path.join(source_dir, "paper_targets", f"{figure}.{fidelity}.json")
        if os.path.isfile(parameter_file):
            run_specs = figure_runs(parameter_file)
        else:
            # A figure without shockgas-sim runs (fig_tail: the far-tail sampler) has its options in its
            # rule, paper_targets/<figure>.cmake, for both fidelities: that file is its parameters.
            parameter_file = os.path.join(source_dir, "paper_targets", f"{figure}.cmake")
            if not os.path.isfile(parameter_file):
                raise Unreadable(f"pack: neither paper_targets/{figure}.{fidelity}.json nor paper_targets/{figure}.cmake "
                                 f"exists in {source_dir}: no figure {figure} at fidelity {fidelity}")
            run_specs = []
        add(f"params/{os.path.basename(parameter_file)}", parameter_file, "parameters", figure,
            f"git: paper_targets/{os.path.basename(parameter_file)} at {version}")
        raw_names = {r["name"] for r in run_specs}
        figure_dir = os.path.join(build_dir, "paper_targets", fidelity, figure)
        candidates = []
        for path in sorted(glob.glob(os.path.join(figure_dir, "*"))):
            base = os.path.basename(path)
            if base.endswith(".args") or base == "simulations.tsv" or re.search(r"\.part\d+\.h5$", base) or ".tmp." in base:
                continue  # configure-time records, merge intermediates, unfinished writes
            candidates.append(path)
        for extension in ("png", "pdf"):
            candidates.append(os.path.join(build_dir, "figures", fidelity, f"{figure}.{extension}"))
        for path in candidates:
            if not os.path.isfile(path):
                raise Unreadable(f"pack: {path} is missing: build the target {figure} first")
            relative = os.path.relpath(path, build_dir)
            category = classify(relative, raw_names)
            extra, archived, command = {}, True, figure_command.format(figure)
            if path.endswith(".h5"):
                objects = h5_walk(path, normalizer)
                extra["content_sha256"] = content_digest(objects)
                extra["provenance"] = provenance(objects)
            if category == "raw":
                spec = next(r for r in run_specs if r["name"] == os.path.basename(path)[:-3])
                command = run_command(spec, "<BUILD>/" + relative)
                archived = os.path.getsize(path) <= max_raw
                runs.append({"figure": figure, "name": spec["name"], "file": "build/" + relative,
                             "options": spec["options"], "parts": spec.get("parts", 1), "command": command,
                             "provenance": extra["provenance"]})
            add("build/" + relative, path, category, figure, command, archived, extra)
        # Theory curves (python/exact_ballistic.py) used by some figures' plots.
        for path in sorted(glob.glob(os.path.join(build_dir, "paper_targets", "theory", "*"))):
            if path not in theory_seen and os.path.isfile(path):
                theory_seen.add(path)
                add("build/" + os.path.relpath(path, build_dir), path, "theory", "theory",
                    "python/exact_ballistic.py --out-dir <BUILD>/paper_targets/theory")

    # The source: a git bundle (history up to the built commit, with tags, so
    # `git describe` gives the same answer) and a snapshot of the working tree
    # as it is now (tracked files plus untracked, not ignored), which carries
    # uncommitted changes when the tree is dirty.
    source_info = {"git_describe": version, "commit": None, "dirty": version.endswith("-dirty")}
    os.makedirs(os.path.join(root, "source"))
    snapshot = os.path.join(root, "source", "working-tree.tar.gz")
    try:
        source_info["commit"] = run(["git", "rev-parse", "HEAD"], cwd=source_dir)
        bundle = os.path.join(root, "source", "shockgas.bundle")
        tags = run(["git", "tag", "--merged", "HEAD"], cwd=source_dir).split()
        run(["git", "bundle", "create", bundle, "HEAD", *tags], cwd=source_dir)
        listed = run(["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                     cwd=source_dir).split("\0")
        tree_files = sorted(f for f in listed if f and os.path.isfile(os.path.join(source_dir, f)))
    except (RuntimeError, OSError):
        tree_files = sorted(os.path.relpath(os.path.join(d, f), source_dir)
                            for d, _, fs in os.walk(source_dir) for f in fs
                            if "/build" not in d and "/.git" not in d)
    with tarfile.open(snapshot, "w:gz") as tar:
        for f in tree_files:
            tar.add(os.path.join(source_dir, f), arcname=f"shockgas/{f}", recursive=False)
    for f in sorted(os.listdir(os.path.join(root, "source"))):
        path = os.path.join(root, "source", f)
        files.append({"path": f"source/{f}", "category": "source", "figure": None, "size": os.path.getsize(path),
                      "sha256": sha256_file(path), "archived": True, "regenerate": None})

    toolchain = dict(item.split("=", 1) for item in args.toolchain)
    manifest = {
        "format": MANIFEST_FORMAT,
        "name": name,
        "created": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
        "created_on": socket.gethostname(),
        "fidelity": fidelity,
        "figures": figures,
        "version": version,
        "source": source_info,
        "build": {"build_dir": build_dir, "source_dir": source_dir, **toolchain},
        "environment": environment_versions(),
        "max_raw_bytes": int(max_raw),
        "regenerate_all": (f"tools/reproduce-check {name}.tar.gz   (or: git clone source/shockgas.bundle; "
                           f"cmake -S shockgas -B build -DCMAKE_BUILD_TYPE={toolchain.get('build_type', 'Release')} "
                           f"-DSHOCKGAS_FIDELITY={fidelity}; cmake --build build --target {' '.join(figures)})"),
        "volatile_attributes": sorted(RUN_DEPENDENT_ATTRIBUTES),
        "runs": runs,
        "files": files,
    }
    with open(os.path.join(root, "MANIFEST"), "w") as handle:
        json.dump(manifest, handle, indent=1, sort_keys=False)
        handle.write("\n")
    with open(os.path.join(root, "SHA256SUMS"), "w") as handle:
        for entry in files:
            if entry["archived"]:
                handle.write(f"{entry['sha256']}  {entry['path']}\n")
    temporary = output + f".tmp.{os.getpid()}"
    try:
        os.makedirs(os.path.dirname(output), exist_ok=True)
        with tarfile.open(temporary, "w:gz") as tar:
            tar.add(root, arcname=name)
        os.replace(temporary, output)
    except OSError as error:  # checked before the packing; a full disk is found only now
        if os.path.exists(temporary):
            os.remove(temporary)
        fail(cannot_write(output, error, "--output-dir" if args.output_dir else "--build-dir"), "reproduce-check pack")
    archived = sum(1 for e in files if e["archived"])
    omitted = [e["path"] for e in files if not e["archived"]]
    print(f"reproduce-check pack: {output}: {archived} files, {os.path.getsize(output) / 1e6:.1f} MB"
          + (f"; {len(omitted)} raw files above {args.max_raw_mb:g} MB listed by SHA-256 only" if omitted else ""))
    return 0


# ---------------------------------------------------------------- checking
class Report:
    def __init__(self):
        self.lines, self.failed, self.notes = [], False, []

    def file(self, status, path, why=""):
        if status not in ("OK", "NOT COMPARED"):
            self.failed = True
        self.lines.append(f"{status:<13} {path}" + (f"  ({why})" if why else ""))

    def note(self, text):
        self.notes.append(text)


def prepare_source(root, manifest, work_dir):
    """Clone the bundle, check out the archived commit, then make the tree equal to
    the archived working-tree snapshot (uncommitted changes included), so that
    `git describe --dirty` in the rebuilt code is the archived one."""
    source = os.path.join(work_dir, "source")
    if os.path.exists(source):
        shutil.rmtree(source)
    bundle = os.path.join(root, "source", "shockgas.bundle")
    commit = manifest["source"].get("commit")
    if os.path.exists(bundle) and commit and shutil.which("git"):
        run(["git", "clone", "--quiet", "--no-checkout", bundle, source])
        run(["git", "-c", "advice.detachedHead=false", "checkout", "--quiet", "--detach", commit], cwd=source)
        tracked = run(["git", "ls-files", "-z"], cwd=source).split("\0")
    else:
        os.makedirs(source)
        tracked = []
    with tarfile.open(os.path.join(root, "source", "working-tree.tar.gz")) as tar:
        members = [m for m in tar.getmembers() if m.name.startswith("shockgas/")]
        snapshot_files = {m.name[len("shockgas/"):] for m in members if m.isfile()}
        for f in tracked:  # deleted in the archived working tree
            if f and f not in snapshot_files and os.path.exists(os.path.join(source, f)):
                os.remove(os.path.join(source, f))
        for member in members:
            member.name = member.name[len("shockgas/"):]
            if member.name:
                tar.extract(member, source)
    return source


class Unreadable(Exception):
    """The archive cannot be checked (exit 2, one line): missing, not an archive, no MANIFEST, or the
    rebuild failed. `keep` names a work directory left for inspection (the rebuild's log)."""

    def __init__(self, message, keep=None):
        super().__init__(message)
        self.keep = keep


# What MANIFEST must hold for the check to read it (docs/archive.md).
MANIFEST_KEYS = ("name", "fidelity", "figures", "created", "created_on", "version", "source", "build", "files")


def unpack(archive, work_dir):
    """Unpacks ARCHIVE under <work_dir>/archive; returns (its root, MANIFEST), or raises Unreadable."""
    unpack_dir = os.path.join(work_dir, "archive")
    if os.path.exists(unpack_dir):
        shutil.rmtree(unpack_dir)
    os.makedirs(unpack_dir)
    try:
        with tarfile.open(archive) as tar:
            tar.extractall(unpack_dir, filter="data") if hasattr(tarfile, "data_filter") else tar.extractall(unpack_dir)
    except (tarfile.TarError, EOFError, OSError, ValueError) as error:  # not a (complete) tar.gz
        why = " ".join(str(error).split())  # tarfile's messages run over several lines
        if isinstance(error, tarfile.ReadError) and "could not be opened" in why:
            why = "not a tar archive (gzip, bzip2, xz or plain)"
        raise Unreadable(f"{archive}: not a readable shockgas archive (.tar.gz): {why}") from None
    tops = os.listdir(unpack_dir)
    if len(tops) != 1 or not os.path.isfile(os.path.join(unpack_dir, tops[0], "MANIFEST")):
        raise Unreadable(f"{archive}: no <name>/MANIFEST inside: not a shockgas archive")
    root = os.path.join(unpack_dir, tops[0])
    try:
        with open(os.path.join(root, "MANIFEST"), encoding="utf-8") as handle:
            manifest = json.load(handle)
    except (ValueError, OSError) as error:
        raise Unreadable(f"{archive}: its MANIFEST is not readable JSON ({error})") from None
    missing = [k for k in MANIFEST_KEYS if not isinstance(manifest, dict) or k not in manifest]
    if missing:
        raise Unreadable(f"{archive}: its MANIFEST lacks {', '.join(missing)}: not a shockgas archive")
    return root, manifest


def check(args):
    """Checks an archive (exit status: docs/archive.md). A temporary work directory is removed on every
    way out, early ones included, unless --keep; after a failed rebuild it is kept for its log."""
    if os.path.isdir(args.archive):  # a build directory: its newest archive
        found = sorted(glob.glob(os.path.join(args.archive, "shockgas-*.tar.gz")), key=os.path.getmtime)
        if not found:
            raise Unreadable(f"no shockgas-*.tar.gz in {args.archive}")
        args.archive = found[-1]
    if not os.path.exists(args.archive):
        raise Unreadable(f"{args.archive}: no such file")
    if not os.path.isfile(args.archive):
        raise Unreadable(f"{args.archive}: not a regular file")
    if args.compare_with and not os.path.isdir(args.compare_with):  # one line, not every file MISSING
        raise Unreadable(f"--compare-with {args.compare_with}: "
                         + ("not a directory" if os.path.exists(args.compare_with) else "no such directory")
                         + " (it names an existing build directory to compare with)")
    if args.work_dir:  # one line, not a traceback from makedirs below
        check_output_directory(args.work_dir, "--work-dir", "reproduce-check")
    temporary = not args.work_dir
    work_dir = os.path.realpath(args.work_dir) if args.work_dir else tempfile.mkdtemp(prefix="shockgas-check-")
    keep = args.keep or not temporary
    try:
        os.makedirs(work_dir, exist_ok=True)
        return check_in(args, work_dir)
    except Unreadable as error:
        if error.keep:
            keep = True
        raise
    finally:
        if not keep:
            shutil.rmtree(work_dir, ignore_errors=True)


def compared_versions(manifest, root, build):
    """The code of BUILD's counterpart of every HDF5 file MANIFEST lists that BUILD has (a missing
    counterpart is reported MISSING by the file comparison), held against the code of the archived file
    (its own attributes; MANIFEST's provenance for a file not archived). Returns ({archive path: the
    counterpart's `version`}, [(path, archived version, compared version, verdict)]), verdict being
    "same simulator" or "different simulator" where both files have a simulator_sha256 that decides
    (same_simulator), else None (the versions decide)."""
    versions, verdicts = {}, []
    for entry in manifest["files"]:
        counterpart = os.path.join(build, entry["path"][len("build/"):])
        if not entry["path"].startswith("build/") or "provenance" not in entry or not os.path.isfile(counterpart):
            continue
        archived_path = os.path.join(root, entry["path"])
        archived = dict(entry["provenance"])
        if entry["archived"] and os.path.isfile(archived_path):
            try:
                archived = attributes(archived_path)
            except (OSError, DamagedFile):  # named by the comparison of the file itself
                pass
        compared = attributes(counterpart)
        version = str(compared.get("version"))
        versions[entry["path"]] = version
        verdicts.append((entry["path"], str(archived.get("version")), version, same_simulator(archived, compared)))
    return versions, verdicts


def code_verdict(verdicts, same_otherwise):
    """(same code?, the words after "code ...: ") from compared_versions' verdicts. A file whose
    simulator_sha256 decides is of the same code when it is the same simulator; another file when
    same_otherwise(path, archived version, compared version) says so (--compare-with: the same version;
    a rerun: the rebuilt source's git describe is the archived one)."""
    different = [v for v in verdicts if v[3] == "different simulator" or (v[3] is None and not same_otherwise(*v[:3]))]
    if different:
        path, archived, compared, verdict = different[0]
        what = "another simulator_sha256" if verdict else "another version"
        return False, (f"DIFFERENT CODE VERSION ({len(different)} of them; first {path}: archived {archived}, "
                       f"compared {compared}: {what})")
    by_hash = [v for v in verdicts if v[3] == "same simulator" and v[1] != v[2]]
    if by_hash:
        path, archived, compared, _ = by_hash[0]
        return True, (f"same simulator ({len(by_hash)} of them made by another version of the same simulator, the "
                      f"same simulator_sha256; first {path}: archived {archived}, compared {compared})")
    return True, "same"


def check_in(args, work_dir):
    root, manifest = unpack(args.archive, work_dir)
    report = Report()
    print(f"archive   {os.path.abspath(args.archive)}\n"
          f"          {manifest['name']}: fidelity {manifest['fidelity']}, figures {' '.join(manifest['figures'])},"
          f" made {manifest['created']} on {manifest['created_on']}")

    # 1. Integrity: every file against its SHA-256 in MANIFEST; nothing extra.
    listed = {e["path"]: e for e in manifest["files"]}
    present = set()
    for directory, _, names in os.walk(root):
        for n in names:
            present.add(os.path.relpath(os.path.join(directory, n), root))
    integrity_bad = {}
    for path in sorted(present - {"MANIFEST", "SHA256SUMS"} - set(listed)):
        report.file("FOREIGN", path, "in the archive but not in MANIFEST")
    for path, entry in listed.items():
        if not entry["archived"]:
            continue
        if path not in present:
            integrity_bad[path] = "MISSING"
        elif sha256_file(os.path.join(root, path)) != entry["sha256"]:
            integrity_bad[path] = "sha256 differs from MANIFEST: the archived file was changed"

    # 2. Source and rebuild (or an existing build to compare with).
    if args.compare_with:
        build = os.path.realpath(args.compare_with)
        source = os.path.realpath(args.source) if args.source else manifest["build"]["source_dir"]
        print(f"rerun     none: comparing with the existing build {build}")
    else:
        source = os.path.realpath(args.source) if args.source else prepare_source(root, manifest, work_dir)
        build = os.path.join(work_dir, "build")
        configure = ["cmake", "-S", source, "-B", build,
                     f"-DCMAKE_BUILD_TYPE={manifest['build'].get('build_type', 'Release')}",
                     f"-DSHOCKGAS_FIDELITY={manifest['fidelity']}",
                     "-DSHOCKGAS_BUILD_TESTS=OFF", "-DSHOCKGAS_BUILD_BENCH=OFF"] + (
                     [f"-DCMAKE_CXX_COMPILER={args.cxx}"] if args.cxx else [])
        targets = list(manifest["figures"])
        # Theory curves packed with the figures are remade by their own target
        # (a figure that does not draw them does not build them).
        if any(e.get("category") == "theory" for e in manifest["files"]):
            targets.append("shockgas_theory")
        build_cmd = ["cmake", "--build", build, "-j", str(args.jobs), "--target", *targets]
        print(f"rerun     source {source}\n          {' '.join(configure)}\n          {' '.join(build_cmd)}",
              flush=True)
        log = os.path.join(work_dir, "rerun.log")
        with open(log, "w") as handle:
            for command in (configure, build_cmd):
                if subprocess.run(command, stdout=handle, stderr=subprocess.STDOUT).returncode != 0:
                    raise Unreadable(f"the rerun failed: {' '.join(command)} (log: {log}; {work_dir} is kept)",
                                     keep=work_dir)
    if args.compare_with:
        # No rerun: the code that made the compared build's files is their own `version` attribute, not
        # the git describe of a checkout (the one MANIFEST names has usually moved on since). Each is
        # held against the version that made its archived counterpart (a run made by an earlier commit
        # whose simulator sources did not change keeps that commit's version, in both builds).
        # Where both files record simulator_sha256, that decides instead: another version of the same
        # simulator (a commit that changed no simulator source) is the same code.
        rerun_versions, verdicts = compared_versions(manifest, root, build)
        same_version, words = code_verdict(verdicts, lambda path, archived, compared: archived == compared)
        compared = ", ".join(sorted(set(rerun_versions.values()))) or "none"
        print(f"code      archive {manifest['version']}, rerun {compared} (the `version` of the compared build's "
              f"{len(rerun_versions)} HDF5 files, each against its archived file's): {words}")
    else:
        # The rebuilt source's git describe against the archived one; where a rerun file and its archived
        # counterpart both record simulator_sha256, that decides for the file instead (--source: another
        # checkout of the same simulator).
        rerun_version = git_describe(source)
        _, verdicts = compared_versions(manifest, root, build)
        same_version, words = code_verdict(verdicts, lambda *_: rerun_version == manifest["version"])
        if not verdicts and rerun_version != manifest["version"]:
            same_version, words = False, "DIFFERENT CODE VERSION"
        elif words == "same" and rerun_version != manifest["version"]:  # every file the same simulator
            words = (f"same simulator (the rerun's {len(verdicts)} HDF5 files have their archived files' "
                     f"simulator_sha256; archived {manifest['version']}, rerun {rerun_version})")
        print(f"code      archive {manifest['version']}, rerun {rerun_version}: {words}")
    if not same_version:
        report.failed = True
    archived_norm = PathNormalizer(manifest["build"]["build_dir"], manifest["build"]["source_dir"])
    rerun_norm = PathNormalizer(build, source)

    # 3. File by file.
    toolchain_cache = {}

    def figure_toolchain_same(figure):
        """Were the figure's runs rerun with the archived compiler, flags, build type and HDF5?"""
        if figure not in toolchain_cache:
            same = True
            for e in manifest["files"]:
                rerun_file = os.path.join(build, e["path"][len("build/"):])
                if e["category"] == "raw" and e["figure"] == figure and os.path.exists(rerun_file):
                    rerun_attrs = {k: attributes(rerun_file).get(k) for k in TOOLCHAIN_ATTRIBUTES}
                    same &= all(rerun_attrs[k] == e["provenance"].get(k) for k in TOOLCHAIN_ATTRIBUTES)
            toolchain_cache[figure] = same
        return toolchain_cache[figure]

    modes = {"exact": 0, "tolerant": 0}
    for entry in manifest["files"]:
        path, category = entry["path"], entry["category"]
        if path in integrity_bad:
            why = integrity_bad[path]
            report.file("MISSING" if why == "MISSING" else "DIFFERENT", path,
                        "listed in MANIFEST, absent from the archive" if why == "MISSING" else why)
            continue
        if category == "source":
            report.file("OK", path, "sha256 matches MANIFEST")
            continue
        if category == "parameters":
            counterpart = os.path.join(source, "paper_targets", os.path.basename(path))
        else:
            counterpart = os.path.join(build, path[len("build/"):])
        if not os.path.exists(counterpart):
            report.file("MISSING", path, f"the rerun did not produce {counterpart}")
            continue
        archived_path = os.path.join(root, path)
        if category in ("raw", "result"):
            if not entry["archived"]:
                objects = h5_walk(counterpart, rerun_norm)
                rerun_prov = provenance(objects)
                if all(rerun_prov.get(k) == entry["provenance"].get(k) for k in TOOLCHAIN_ATTRIBUTES):
                    if content_digest(objects) == entry["content_sha256"]:
                        report.file("OK", path, f"not archived ({entry['size'] / 1e6:.0f} MB): content SHA-256 matches")
                    else:
                        report.file("DIFFERENT", path, "not archived: content SHA-256 of the rerun differs")
                else:
                    report.file("NOT COMPARED", path, "not archived and the toolchain differs; "
                                "the results computed from it are compared")
                continue
            exact, differences, version_note = compare_h5(archived_path, counterpart, archived_norm, rerun_norm,
                                                          args.sigma_factor)
            modes["exact" if exact else "tolerant"] += 1
            notes = [] if not version_note else [version_note]
            if differences:
                shown = differences[:args.max_details]
                more = len(differences) - len(shown)
                report.file("DIFFERENT", path, "; ".join(shown + ([f"{more} more"] if more > 0 else []) + notes))
            else:
                what = ("bit-identical datasets and attributes" if exact else
                        f"toolchain differs: numbers X with X_sigma agree within {args.sigma_factor:g} sigma")
                report.file("OK", path, "; ".join([what] + notes))
            continue
        toolchain_same = figure_toolchain_same(entry["figure"]) if category in ("data", "figure") else True
        why = compare_bytes(archived_path, counterpart, category, archived_norm, rerun_norm)
        if why is None:
            aside = ("" if category in ("parameters",) or path.endswith(".png") else
                     " (creation date aside)" if path.endswith(".pdf") else " (build paths aside)")
            report.file("OK", path, "identical" + aside)
        elif not toolchain_same:
            report.file("NOT COMPARED", path, f"toolchain differs, byte comparison not meaningful: {why}")
        elif category == "figure" and entry["figure"] in FIGURES_PLOTTING_COSTS:
            report.file("NOT COMPARED", path, f"{FIGURES_PLOTTING_COSTS[entry['figure']]}; its numbers are "
                        "compared in its data files")
        else:
            report.file("DIFFERENT", path, why)

    print()
    for line in report.lines:
        print(line)
    counts = {}
    for line in report.lines:
        status = line[:13].strip()
        counts[status] = counts.get(status, 0) + 1
    print("\nsummary   " + ", ".join(f"{v} {k}" for k, v in sorted(counts.items()))
          + f"; HDF5 compared exactly: {modes['exact']}, within sigma: {modes['tolerant']}"
          + ("" if same_version else "; code version differs"))
    print("result    " + ("REPRODUCED" if not report.failed else "NOT REPRODUCED"))
    return 1 if report.failed else 0


def command_line(argv):
    """Parses tools/reproduce-check's arguments and packs (`pack ...`) or checks (`[check] ARCHIVE ...`)."""
    if argv and argv[0] == "pack":
        parser = ArgumentParser(prog="reproduce-check pack", description="write an archive")
        parser.add_argument("--build-dir", required=True)
        parser.add_argument("--source-dir", required=True)
        parser.add_argument("--fidelity", required=True)
        parser.add_argument("--figures", required=True, help="list separated by ; , or spaces")
        parser.add_argument("--output-dir", help="default: the build directory")
        parser.add_argument("--suffix", default="", help="appended to the archive's name")
        parser.add_argument("--max-raw-mb", type=float, default=DEFAULT_MAX_RAW_MB,
                            help="raw HDF5 files above this size are listed by SHA-256 only (default 50)")
        parser.add_argument("--toolchain", nargs="*", default=[], metavar="KEY=VALUE",
                            help="build facts recorded in MANIFEST (compiler, compiler_flags, build_type, ...)")
        return pack(parser.parse_args(argv[1:]))
    if argv and argv[0] == "check":
        argv = argv[1:]
    parser = ArgumentParser(prog="reproduce-check", description=USAGE,
                            formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("archive", help="the .tar.gz, or a directory: its newest shockgas-*.tar.gz")
    parser.add_argument("--work-dir", help="where to unpack, check out and rebuild (kept); default: a temporary "
                                           "directory, removed afterwards")
    parser.add_argument("--keep", action="store_true", help="keep the temporary work directory")
    parser.add_argument("--source", help="use this source tree instead of the archived one")
    parser.add_argument("--compare-with", metavar="BUILD", help="compare with this existing build directory "
                                                                "instead of rebuilding")
    parser.add_argument("--cxx", help="C++ compiler for the rebuild (CMAKE_CXX_COMPILER)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    parser.add_argument("--sigma-factor", type=float, default=DEFAULT_SIGMA_FACTOR)
    parser.add_argument("--max-details", type=int, default=3)
    args = parser.parse_args(argv)
    return check(args)


def main(argv):
    """tools/reproduce-check with the arguments argv (sys.argv[1:]): `pack ...` writes an archive,
    anything else checks one (USAGE). Returns the exit status; an archive that cannot be checked, a
    command that failed or a damaged file is one line "reproduce-check: error: ..." and exit status 2."""
    try:
        return command_line(argv)
    except (Unreadable, RuntimeError, DamagedFile) as error:  # one line naming the file
        fail(error, "reproduce-check")
