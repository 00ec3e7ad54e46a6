#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks on the tracked files of the source tree (label docs).

    check_repository.py SOURCE_DIR machine-paths | hdf5-readers | doc-links | readme-entry

machine-paths  no tracked file points outside the repository: at the folder it was cloned into,
               at a sibling checkout's shared folder, or at a user's home or this machine's own
               folders. A user's clone has none of them. The system's folders (/usr/bin/python3,
               /tmp) are the same on every Debian machine and allowed.
hdf5-readers   Python opens shockgas's HDF5 files for reading in one place, python/shockgas (as
               C++ does in sim/io/include/shockgas/io/h5.hpp): any other h5py.File( must name a writing
               mode ("w", "r+", "a", "x", "w-"): tests that make or damage files on purpose.
doc-links      every relative link in a tracked Markdown file reaches a tracked file, and every
               #anchor a heading of its page (GitHub's heading slugs).
readme-entry   README.md stays an entry point for users, not a log of measurements:
               - at most 150 lines;
               - the test command stands where .ci/run reads it (an indented line two lines after
                 "Install, build and run the tests");
               - the word "machine" only as the reader's own: "your machine(s)" or "a fresh Debian
                 machine" (the first command's). The computers a measurement ran on are hardware in
                 docs/measurements.md, never a "machine" of the README;
               - dates (YYYY-MM-DD) and commit hashes (7 to 40 hex digits, at least one a digit and
                 one a letter) only on the version line of the results table: the first non-blank line
                 after the table whose header is "| claim | quick tier | paper tier | paper / theory |".
Exit status 0 ok, 1 a problem (each printed with file and line), 77 (SKIP) outside a git checkout.
"""
import os
import re
import subprocess
import sys

source, check = os.path.realpath(sys.argv[1]), sys.argv[2]
try:
    tracked = subprocess.run(["git", "ls-files", "-z"], cwd=source, check=True, capture_output=True).stdout
except (OSError, subprocess.CalledProcessError) as error:
    print(f"SKIP: {source} is not a git checkout ({error})")
    sys.exit(77)
tracked = sorted(name for name in tracked.decode().split("\0") if name)


def text_lines(name):
    try:
        with open(os.path.join(source, name), encoding="utf-8") as handle:
            return handle.read().splitlines()
    except (UnicodeDecodeError, IsADirectoryError, FileNotFoundError):
        return []  # binary (test data), a submodule, or deleted in the work tree


problems = []

if check == "machine-paths":
    # Spelt in pieces so that this file does not match itself.
    shared = ".." + "/shared"
    machine_folder = re.compile(r"(?<![\w.}\-/~$])/(?:" + "|".join(["work", "home", "root", "Users", "mnt",
                                                                       "scratch", "media"]) + r")/")
    checked = 0
    for name in tracked:
        for number, line in enumerate(text_lines(name), 1):
            checked += 1
            if shared in line:
                problems.append(f"{name}:{number}: points at {shared}: {line.strip()}")
            elif len(source) > 5 and source in line:
                problems.append(f"{name}:{number}: names this checkout's folder {source}: {line.strip()}")
            elif machine_folder.search(line):
                problems.append(f"{name}:{number}: names a folder of a machine: {line.strip()}")
    print(f"{len(tracked)} tracked files, {checked} lines checked")

elif check == "hdf5-readers":
    call = re.compile(r"h5py\.File\(([^()]*(?:\([^()]*\)[^()]*)*)\)")
    writing = re.compile(r"""(?:^|,)\s*(?:mode\s*=\s*)?["'](w|r\+|a|x|w-)["']\s*(?:,|$)""")
    calls = 0
    for name in tracked:
        if name.startswith("python/shockgas/"):
            continue
        for number, line in enumerate(text_lines(name), 1):
            for match in call.finditer(line):
                calls += 1
                if not writing.search(match.group(1)):
                    problems.append(f"{name}:{number}: reads HDF5 with h5py itself; use the shockgas module "
                                    f"(shockgas.read_run, read_results, attributes, walk, ...): {line.strip()}")
    print(f"{calls} h5py.File calls outside python/shockgas, all writing" if not problems else "")

elif check == "doc-links":
    link = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")
    tracked_set = set(tracked)

    def slugs(name):
        """GitHub's heading anchors: lower case, punctuation dropped, spaces to hyphens, repeats numbered."""
        seen, found, fenced = {}, set(), False
        for line in text_lines(name):
            if line.startswith("```"):
                fenced = not fenced
            if fenced or not re.match(r"#{1,6} ", line):
                continue
            slug = re.sub(r"[^\w\- ]", "", line.lstrip("#").strip().lower()).replace(" ", "-")
            found.add(slug if slug not in seen else f"{slug}-{seen[slug]}")
            seen[slug] = seen.get(slug, 0) + 1
        return found

    links = 0
    for name in (n for n in tracked if n.endswith(".md")):
        for number, line in enumerate(text_lines(name), 1):
            for target in link.findall(line):
                if re.match(r"[a-z]+:", target):
                    continue  # https:, mailto:
                links += 1
                path, _, anchor = target.partition("#")
                resolved = os.path.normpath(os.path.join(os.path.dirname(name), path)) if path else name
                if resolved not in tracked_set and not any(t.startswith(resolved + "/") for t in tracked):
                    problems.append(f"{name}:{number}: link to {target}: no tracked file {resolved}")
                elif anchor and resolved.endswith(".md") and anchor not in slugs(resolved):
                    problems.append(f"{name}:{number}: link to {target}: {resolved} has no heading #{anchor}")
    print(f"{links} relative links checked")

elif check == "readme-entry":
    lines = text_lines("README.md")
    if len(lines) > 150:
        problems.append(f"README.md: {len(lines)} lines, more than 150: the details belong in docs/")
    heading = [i for i, line in enumerate(lines) if line.startswith("Install, build and run the tests")]
    if not heading or len(lines) <= heading[0] + 2 or not lines[heading[0] + 2].startswith("    "):
        problems.append("README.md: no indented test command two lines after 'Install, build and run the tests' "
                        "(.ci/run reads it there)")
    header = "| claim | quick tier | paper tier | paper / theory |"
    version_line = None
    if header in lines:
        after = lines.index(header)
        while after < len(lines) and lines[after].startswith("|"):
            after += 1
        version_line = next((i for i in range(after, len(lines)) if lines[i].strip()), None)
    else:
        problems.append(f"README.md: no results table (header {header})")
    machine = re.compile(r"machines?\b", re.I)
    own = re.compile(r"(?:\byour|\bDebian) machines?\b", re.I)
    date = re.compile(r"\b\d{4}-\d{2}-\d{2}\b")
    commit = re.compile(r"\b(?=[0-9a-f]*[a-f])(?=[0-9a-f]*[0-9])[0-9a-f]{7,40}\b")
    for number, line in enumerate(lines, 1):
        if len(machine.findall(line)) > len(own.findall(line)):
            problems.append(f"README.md:{number}: 'machine' not as the reader's own (name hardware in "
                            f"docs/measurements.md): {line.strip()}")
        if number - 1 != version_line:
            for found in date.findall(line) + commit.findall(line):
                problems.append(f"README.md:{number}: {found} outside the results table's version line "
                                f"(dated measurements go in docs/measurements.md): {line.strip()}")
    print(f"README.md: {len(lines)} lines checked")

else:
    sys.exit(f"unknown check {check!r}")

for problem in problems:
    print("FAIL:", problem)
sys.exit(1 if problems else 0)
