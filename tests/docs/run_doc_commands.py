#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Runs the commands of a user's page exactly as written, in a checkout that looks like a user's
after the README's first command (label docs).

    run_doc_commands.py SOURCE_DIR WORK_DIR PYTHON BIN_DIR[:BIN_DIR...] PAGE.md [PAGE.md ...]

A page's commands are its fenced code blocks whose info string is `sh` or `python`, in page order. A
block is an illustration, not run, when the line before its fence is `<!-- illustration: not run -->`.
Indented blocks and blocks of any other language (`text` for a program's output) are never run. A page
with no block to run fails: a page whose commands became indented blocks would otherwise pass unseen.

The checkout is WORK_DIR/checkout: every top-level entry of SOURCE_DIR but its build trees, linked, and
`build/bin` holding the programs of the BIN_DIRs (the build's own programs, linked under their names).
The `sh` blocks of one page run one after another in one bash session started in the checkout (so an
`export` or a `cd` in one block holds in the next), under `set -e`, with PATH reduced to the system's
folders, so that a page which forgets to say where the programs are fails. A `python` block runs there
too, as `python3 - <<EOF`, with the python3 that is PYTHON (Debian's /usr/bin/python3, which has numpy
and h5py) and the session's environment (a PYTHONPATH the page exported).

Exit status 0 if every block of every page ran, 1 naming the page and the line of the block that failed,
2 for a mistake in the arguments.
"""
import os
import re
import shutil
import subprocess
import sys

ILLUSTRATION = "<!-- illustration: not run -->"


def blocks(page):
    """(line of the fence, language, text) of each fenced block to run, in page order."""
    with open(page, encoding="utf-8") as handle:
        lines = handle.read().splitlines()
    found, i = [], 0
    while i < len(lines):
        fence = re.match(r"^(```+)\s*([\w-]*)", lines[i])
        if not fence:
            i += 1
            continue
        end = next((j for j in range(i + 1, len(lines)) if lines[j].startswith(fence.group(1))), None)
        if end is None:
            sys.exit(f"run_doc_commands: {page}:{i + 1}: a fence that never closes")
        language = fence.group(2)
        illustration = i > 0 and lines[i - 1].strip() == ILLUSTRATION
        if language in ("sh", "python") and not illustration:
            found.append((i + 1, language, "\n".join(lines[i + 1:end])))
        i = end + 1
    return found


def make_checkout(source, work, bins):
    checkout = os.path.join(work, "checkout")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(os.path.join(checkout, "build", "bin"))
    for entry in os.listdir(source):
        if entry.startswith("build") or entry.startswith("."):
            continue  # build trees (build, build-ci, ...) and .git: a user's clone has its own
        os.symlink(os.path.join(source, entry), os.path.join(checkout, entry))
    programs = 0
    for directory in bins:
        for name in sorted(os.listdir(directory)):
            path = os.path.join(directory, name)
            target = os.path.join(checkout, "build", "bin", name)
            if os.path.isfile(path) and os.access(path, os.X_OK) and not os.path.lexists(target):
                os.symlink(path, target)
                programs += 1
    shim = os.path.join(work, "python-shim")
    os.makedirs(shim)
    return checkout, shim, programs


def script_of(page, found):
    """The page's blocks as one bash script, each announced on stderr with its line."""
    parts = ["set -e"]
    for line, language, text in found:
        parts.append(f"echo '== {os.path.basename(page)}:{line} ({language})'")
        if language == "sh":
            parts.append(text)
        else:
            marker = "SHOCKGAS_DOC_PYTHON_BLOCK"
            parts.append(f"python3 - <<'{marker}'\n{text}\n{marker}")
    return "\n".join(parts) + "\n"


def main(argv):
    if len(argv) < 6:
        print(__doc__.strip().splitlines()[2].strip(), file=sys.stderr)
        return 2
    source, work, python, bins, pages = (os.path.realpath(argv[1]), os.path.realpath(argv[2]), argv[3],
                                         [d for d in argv[4].split(":") if d], argv[5:])
    checkout, shim, programs = make_checkout(source, work, bins)
    os.symlink(python, os.path.join(shim, "python3"))
    if programs == 0:
        print(f"run_doc_commands: no programs in {', '.join(bins)}", file=sys.stderr)
        return 2
    environment = {"PATH": f"{shim}:/usr/local/bin:/usr/bin:/bin", "HOME": work, "LANG": "C.UTF-8",
                   "TMPDIR": os.environ.get("TMPDIR", "/tmp")}
    failed = []
    for page in pages:
        found = blocks(os.path.join(source, page))
        if not found:
            failed.append(f"{page}: no fenced sh or python block to run")
            continue
        script = os.path.join(work, os.path.basename(page) + ".sh")
        with open(script, "w", encoding="utf-8") as handle:
            handle.write(script_of(page, found))
        print(f"run_doc_commands: {page}: {len(found)} blocks, in {checkout}", flush=True)
        result = subprocess.run(["bash", script], cwd=checkout, env=environment, stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True)
        print(result.stdout, end="", flush=True)
        if result.returncode != 0:
            announced = re.findall(r"^== (\S+:\d+) \((\w+)\)$", result.stdout, re.M)
            where = f"the block at {announced[-1][0]}" if announced else "before its first block"
            failed.append(f"{page}: {where} failed (exit status {result.returncode})")
    for failure in failed:
        print("FAIL:", failure)
    if not failed:
        print(f"ok: every block of {', '.join(pages)} ran")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
