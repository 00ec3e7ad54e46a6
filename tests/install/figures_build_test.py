#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""figures_build_test.py SOURCE_DIR WORK_DIR (label install; docs/install.md)

`cmake --install` after the README's first build, which is `--target figures`, not the whole
tree. Configures a fresh tree with the quick preset's cache variables (no compiling), then:
  1. asks CMake (its file API) what `--target figures` builds, and what the installation takes
     from the build tree: every installed target and every file made in the build tree must be
     among the things `figures` builds (the man pages among them, or the install stops on them);
  2. makes the tree look built except for the man pages (the programs and libraries as empty
     files) and installs: the install must refuse, naming the missing pages and the command
     that makes them, and leave the prefix empty (not half filled);
  3. adds the pages and installs again: the programs and man pages are in the prefix.
"""
import json
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

source, work = pathlib.Path(sys.argv[1]).resolve(), pathlib.Path(sys.argv[2]).resolve()


def fail(message):
    print(f"FAIL: {message}")
    sys.exit(1)


def preset_cache_variables(name):
    """The cache variables of a configure preset, with those it inherits."""
    presets = {p["name"]: p for p in json.loads((source / "CMakePresets.json").read_text())["configurePresets"]}
    preset = presets[name]
    variables = {}
    for parent in preset.get("inherits", []) if isinstance(preset.get("inherits"), list) else [preset.get("inherits")]:
        if parent:
            variables.update(preset_cache_variables(parent))
    variables.update(preset.get("cacheVariables", {}))
    return variables


shutil.rmtree(work, ignore_errors=True)
tree = work / "tree"
query = tree / ".cmake/api/v1/query/codemodel-v2"
query.parent.mkdir(parents=True)
query.touch()
# Tests and benchmarks are neither installed nor needed by the figures: left out, the configure is quicker.
variables = {**preset_cache_variables("quick"), "SHOCKGAS_BUILD_TESTS": "OFF", "SHOCKGAS_BUILD_BENCH": "OFF"}
configure = subprocess.run(["cmake", "-S", str(source), "-B", str(tree)] + [f"-D{k}={v}" for k, v in variables.items()],
                           capture_output=True, text=True)
if configure.returncode != 0:
    fail(f"configuring a tree with the quick preset's variables:\n{configure.stdout}{configure.stderr}")

# 1. What `--target figures` builds, against what the installation takes from the tree.
reply = tree / ".cmake/api/v1/reply"
codemodel = json.loads(next(reply.glob("codemodel-v2-*.json")).read_text())
configuration = codemodel["configurations"][0]
targets = {t["id"]: json.loads((reply / t["jsonFile"]).read_text()) for t in configuration["targets"]}
by_name = {t["name"]: i for i, t in targets.items()}
if "figures" not in by_name:
    fail("the quick preset's tree has no target 'figures'")
built, stack = set(), [by_name["figures"]]
while stack:
    target = stack.pop()
    if target not in built:
        built.add(target)
        stack += [d["id"] for d in targets[target].get("dependencies", [])]

def absolute(path):
    """A path of the file API's reply: relative ones are relative to the source tree."""
    return pathlib.Path(path) if os.path.isabs(path) else source / path


# A file made by a custom command shows among its target's sources (as itself, or as <file>.rule).
made = {absolute(s["path"].removesuffix(".rule")) for t in built for s in targets[t].get("sources", [])
        if s.get("isGenerated")}
problems, installed_targets = [], []
for directory in configuration["directories"]:
    for installer in json.loads((reply / directory["jsonFile"]).read_text()).get("installers", []):
        kind = installer["type"]
        if kind == "target":
            installed_targets.append(installer)
            ids = [installer["targetId"]]
        elif kind == "export":
            ids = [t["id"] for t in installer["exportTargets"]]
        else:
            ids = []
        # An interface library (shockgas::sim) is not in the code model: nothing of it is built.
        problems += [f"target {targets[i]['name']}" for i in ids if i in targets and i not in built]
        if kind == "file":
            for path in installer["paths"]:
                path = absolute(path)
                # In the build tree and not written by the configure: made by the build.
                if tree in path.parents and not path.exists() and path not in made:
                    problems.append(str(path.relative_to(tree)))
if problems:
    fail(f"installed, but not built by `cmake --build --target figures`: {', '.join(sorted(set(problems)))}")
print(f"figures builds every installed target ({len(installed_targets)}) and every installed file made in the build tree")

# 2. A tree built but for its man pages.
for installer in installed_targets:
    for path in installer["paths"]:
        program = tree / path
        program.parent.mkdir(parents=True, exist_ok=True)
        program.write_bytes(b"")
        program.chmod(0o755)
pages = sorted((tree / "man").glob("*.1.gz")) if (tree / "man").exists() else []
if pages:
    fail(f"the fresh tree already has man pages: {pages}")
prefix = pathlib.Path(tempfile.mkdtemp(dir=work, prefix="prefix."))
install = subprocess.run(["cmake", "--install", str(tree), "--prefix", str(prefix)], capture_output=True, text=True)
said = " ".join((install.stdout + install.stderr).split())  # CMake wraps its messages
left = [str(p.relative_to(prefix)) for p in prefix.rglob("*") if not p.is_dir()]
if install.returncode == 0:
    fail(f"installing a tree without man pages succeeded:\n{said}")
if left:
    fail(f"the refused install left {len(left)} files in the prefix, e.g. {left[:3]}:\n{said}")
if "man/shockgas-sim.1.gz" not in said or f"cmake --build {tree}" not in said:
    fail(f"the refusal does not name the missing man page and the command that makes it:\n{said}")
print("without man pages: refused, prefix left empty")

# 3. With the pages, the same install goes through.
manifest = [line for line in (tree / "install-needs.txt").read_text().splitlines() if "/man/" in line]
for line in manifest:
    page = pathlib.Path(line.split("\t", 1)[1])
    page.write_bytes(b"")
install = subprocess.run(["cmake", "--install", str(tree), "--prefix", str(prefix)], capture_output=True, text=True)
if install.returncode != 0:
    fail(f"installing the complete tree:\n{install.stdout}{install.stderr}")
expected = [f"bin/{p}" for p in ("shockgas-sim", "shockgas-analyze", "shockgas-look")] + \
           [f"share/man/man1/{p}.1.gz" for p in ("shockgas-sim", "shockgas-tail")]
absent = [p for p in expected if not (prefix / p).exists()]
if absent or not manifest:
    fail(f"after the install the prefix lacks {absent} (man pages listed: {len(manifest)})")
print(f"ok: installed from a tree built as `--target figures` builds it ({len(manifest)} man pages)")
