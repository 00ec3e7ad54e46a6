#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""tools/reproduce-check on archives it cannot read: exit 2, one line, no temporary left behind
(ctest python.reproduce_check_unreadable, label python; < 1 s).

    test_reproduce_check_cli.py WORK_DIR

docs/archive.md gives exit status 1 the meaning NOT REPRODUCED and 2 an unreadable archive. A missing
archive or a file that is not one must not give a Python traceback and exit status 1, nor an early
exit leave its temporary work directory (/tmp/shockgas-check-*) behind. Each case below runs the tool with
TMPDIR set to an empty directory of its own, and asserts exit status 2, one stderr line
"reproduce-check: error: ..." naming what is wrong, and that directory empty afterwards: a missing
archive, a text file, a gzip file that is not a tar archive, a tar.gz cut short, a tar.gz without
MANIFEST, one whose MANIFEST is not JSON, one whose MANIFEST lacks the fields, a directory
holding no archive, and a --compare-with directory that does not exist (not every file of the
archive reported MISSING, exit 1).

CompareWith packs a miniature build (one results file, its figure) of a git checkout, commits once
more in that checkout, and checks the archive against the same, unchanged build with --compare-with.
The code version is the compared files' own `version` attribute: every file is the archived one, so
the check must say "same" and REPRODUCED (exit 0), not read `git describe` of the checkout MANIFEST
names, which has moved on, and report DIFFERENT CODE VERSION and NOT REPRODUCED (exit 1). A
compared file of another simulator (another `version` and simulator_sha256, or the same version and
another simulator_sha256) is still named, DIFFERENT CODE VERSION, exit 1; so is one of another version
without simulator_sha256 (written by a build that did not record it). A bit-identical file of another
version of the same simulator (the same simulator_sha256) reproduces: "same simulator", naming both
versions, exit 0 (not DIFFERENT CODE VERSION, exit 1). simulator_sha256 and input_simulator_sha256 are
provenance, never compared as data: a result whose input_simulator_sha256 alone differs reproduces
(not DIFFERENT, naming the attribute).
"""
import glob
import gzip
import io
import json
import os
import shutil
import subprocess
import tarfile
import unittest

import script_checks as sc

h5py, _ = sc.require("h5py", "numpy")
import shockgas.schema  # noqa: E402

WORK = sc.arguments(1)
TOOL = sc.script("tools", "reproduce-check")
NAME = "reproduce-check"
# The simulator_sha256 of the miniature build's files, and another simulator's.
SIMULATOR, OTHER_SIMULATOR = "a" * 64, "b" * 64


def archive(name, members):
    """A tar.gz under WORK holding `members` (archive path -> bytes)."""
    target = os.path.join(WORK, name)
    with tarfile.open(target, "w:gz") as tar:
        for member, data in members.items():
            info = tarfile.TarInfo(member)
            info.size = len(data)
            tar.addfile(info, io.BytesIO(data))
    return target


class Unreadable(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        shutil.rmtree(WORK, ignore_errors=True)
        os.makedirs(WORK)

    def check(self, name, target, *words):
        """Runs the check on `target` with a private TMPDIR; asserts the one-line refusal and no leftover."""
        temporary = os.path.join(WORK, "tmp-" + name)
        os.makedirs(temporary)
        env = dict(os.environ, TMPDIR=temporary)
        result = sc.run([sc.PYTHON, TOOL, target], cwd=WORK, env=env)
        sc.one_line_error(self, result, NAME, *words)
        self.assertEqual(os.listdir(temporary), [], f"{name}: a temporary work directory was left behind")

    def test_missing_archive(self):
        self.check("missing", os.path.join(WORK, "no-such-archive.tar.gz"), "no-such-archive.tar.gz", "no such file")

    def test_not_an_archive(self):
        text = os.path.join(WORK, "notes.tar.gz")
        with open(text, "w") as handle:
            handle.write("not an archive\n")
        self.check("text", text, "notes.tar.gz", "not a tar archive")
        gz = os.path.join(WORK, "plain.gz")
        with gzip.open(gz, "wb") as handle:
            handle.write(b"x" * 1000)
        self.check("gzip", gz, "plain.gz", "not a readable shockgas archive")

    def test_cut_short(self):
        whole = archive("whole.tar.gz", {"shockgas-x/MANIFEST": b"{}", "shockgas-x/big": os.urandom(200000)})
        with open(whole, "rb") as handle:
            data = handle.read()
        cut = os.path.join(WORK, "cut.tar.gz")
        with open(cut, "wb") as handle:
            handle.write(data[:len(data) // 2])
        self.check("cut", cut, "cut.tar.gz", "not a readable shockgas archive")

    def test_no_manifest(self):
        self.check("nomanifest", archive("nomanifest.tar.gz", {"shockgas-x/README": b"hello\n"}),
                   "no <name>/MANIFEST")

    def test_manifest_not_json(self):
        self.check("badjson", archive("badjson.tar.gz", {"shockgas-x/MANIFEST": b"{not json"}), "not readable JSON")

    def test_manifest_without_fields(self):
        manifest = json.dumps({"format": 1, "name": "shockgas-x"}).encode()
        self.check("fields", archive("fields.tar.gz", {"shockgas-x/MANIFEST": manifest}), "MANIFEST lacks",
                   "fidelity")

    def test_directory_without_archives(self):
        empty = os.path.join(WORK, "empty-build")
        os.makedirs(empty, exist_ok=True)
        self.check("emptydir", empty, "no shockgas-*.tar.gz")

    def test_compare_with_no_such_build(self):
        target = archive("compare.tar.gz", {"shockgas-x/MANIFEST": json.dumps(
            {"name": "shockgas-x", "fidelity": "quick", "figures": [], "created": "", "created_on": "", "version": "v",
             "source": {}, "build": {"build_dir": "/b", "source_dir": "/s"}, "files": []}).encode()})
        temporary = os.path.join(WORK, "tmp-compare")
        os.makedirs(temporary)
        result = sc.run([sc.PYTHON, TOOL, target, "--compare-with", os.path.join(WORK, "no-such-build")], cwd=WORK,
                        env=dict(os.environ, TMPDIR=temporary))
        sc.one_line_error(self, result, NAME, "--compare-with", "no-such-build", "no such directory")
        self.assertEqual(os.listdir(temporary), [])
        result = sc.run([sc.PYTHON, TOOL, target, "--compare-with", target], cwd=WORK, env=dict(os.environ, TMPDIR=temporary))
        sc.one_line_error(self, result, NAME, "--compare-with", "not a directory")


class CompareWith(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        if shutil.which("git") is None:  # pragma: no cover - depends on the machine
            raise unittest.SkipTest("needs git")
        cls.root = os.path.join(WORK, "compare-with")
        shutil.rmtree(cls.root, ignore_errors=True)
        cls.source, cls.build = os.path.join(cls.root, "source"), os.path.join(cls.root, "build")
        os.makedirs(os.path.join(cls.source, "paper_targets"))
        with open(os.path.join(cls.source, "paper_targets", "figx.quick.json"), "w") as handle:
            json.dump({"runs": []}, handle)
        cls.git("init", "--quiet")
        cls.git("add", ".")
        cls.git("commit", "--quiet", "-m", "one")
        version = cls.git("describe", "--always", "--dirty", "--tags")
        figure = os.path.join(cls.build, "paper_targets", "quick", "figx")
        os.makedirs(figure)
        os.makedirs(os.path.join(cls.build, "figures", "quick"))
        cls.result = os.path.join(figure, "result.h5")
        with h5py.File(cls.result, "w") as f:  # as the build at that commit wrote it
            f.attrs.update({"program": "shockgas-analyze scaling", "version": version, "date": "2026-11-28",
                            "simulator_sha256": SIMULATOR, "input_simulator_sha256": SIMULATOR,
                            "input_version": version,
                            "schema_version": max(shockgas.schema.SCHEMA_VERSIONS), "beta": 0.335, "beta_sigma": 0.01})
            f["z"] = [0.5, 1.0, 1.5]
        for extension in ("png", "pdf"):
            with open(os.path.join(cls.build, "figures", "quick", "figx." + extension), "wb") as handle:
                handle.write(b"a figure\n")
        packed = sc.run([sc.PYTHON, TOOL, "pack", "--build-dir", cls.build, "--source-dir", cls.source,
                         "--fidelity", "quick", "--figures", "figx"], cwd=cls.root)
        assert packed.returncode == 0, packed.stdout + packed.stderr
        cls.archive = glob.glob(os.path.join(cls.build, "shockgas-*.tar.gz"))[0]
        # The checkout goes on; the build stays as it was.
        with open(os.path.join(cls.source, "later.txt"), "w") as handle:
            handle.write("a later commit\n")
        cls.git("add", ".")
        cls.git("commit", "--quiet", "-m", "two")
        cls.version = version

    @classmethod
    def git(cls, *arguments):
        return subprocess.run(["git", "-c", "user.name=test", "-c", "user.email=test@example.org", *arguments],
                              cwd=cls.source, check=True, capture_output=True, text=True).stdout.strip()

    def check(self, *extra):
        return sc.run([sc.PYTHON, TOOL, self.archive, "--compare-with", self.build,
                       "--work-dir", os.path.join(self.root, "work"), *extra], cwd=self.root)

    def test_an_unchanged_build_reproduces(self):
        result = self.check()
        described = result.stdout + result.stderr
        self.assertEqual(result.returncode, 0, described)
        self.assertRegex(result.stdout, rf"(?m)^code +archive {self.version}, rerun {self.version} .*: same$")
        self.assertRegex(result.stdout, r"(?m)^OK +build/paper_targets/quick/figx/result.h5 +\(bit-identical")
        self.assertRegex(result.stdout, r"(?m)^result +REPRODUCED$")
        self.assertNotIn("DIFFERENT", result.stdout)

    def compare_with_changed(self, name, **attributes):
        """The check against a copy of the build whose result.h5 has `attributes` set (None: removed)."""
        other = os.path.join(self.root, name)
        shutil.rmtree(other, ignore_errors=True)
        shutil.copytree(self.build, other)
        with h5py.File(os.path.join(other, "paper_targets", "quick", "figx", "result.h5"), "r+") as f:
            for key, value in attributes.items():
                if value is None:
                    del f.attrs[key]
                else:
                    f.attrs[key] = value
        return sc.run([sc.PYTHON, TOOL, self.archive, "--compare-with", other,
                       "--work-dir", os.path.join(self.root, "work-" + name)], cwd=self.root)

    def test_a_file_of_another_simulator_is_named(self):
        # Another version and another simulator_sha256: another simulator.
        result = self.compare_with_changed("other-build", version="v9.9-1-gdeadbee", simulator_sha256=OTHER_SIMULATOR)
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertRegex(result.stdout, rf"(?m)^code +archive {self.version}, rerun v9.9-1-gdeadbee .*: DIFFERENT "
                                        rf"CODE VERSION \(1 of them; first build/paper_targets/quick/figx/result.h5: "
                                        rf"archived {self.version}, compared v9.9-1-gdeadbee: another simulator_sha256")
        self.assertRegex(result.stdout, r"(?m)^result +NOT REPRODUCED$")
        # The same version, another simulator_sha256 (two edits of an uncommitted tree), same toolchain.
        result = self.compare_with_changed("edited-build", simulator_sha256=OTHER_SIMULATOR)
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertRegex(result.stdout, r"(?m)^code .*: DIFFERENT CODE VERSION .*another simulator_sha256")

    def test_a_file_of_another_version_without_a_simulator_hash_is_named(self):
        # A file written before simulator_sha256 (removed here): its version decides, as before.
        result = self.compare_with_changed("old-build", version="v9.9-1-gdeadbee", simulator_sha256=None)
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertRegex(result.stdout, rf"(?m)^code +archive {self.version}, rerun v9.9-1-gdeadbee .*: DIFFERENT "
                                        rf"CODE VERSION \(1 of them; first build/paper_targets/quick/figx/result.h5: "
                                        rf"archived {self.version}, compared v9.9-1-gdeadbee: another version\)")
        self.assertRegex(result.stdout, r"(?m)^result +NOT REPRODUCED$")

    def test_another_version_of_the_same_simulator_reproduces(self):
        # A bit-identical file made by another version of the same simulator (the same simulator_sha256: a
        # commit that changed no simulator source): reproduced, not DIFFERENT CODE VERSION, NOT REPRODUCED.
        result = self.compare_with_changed("same-simulator-build", version="v9.9-1-gdeadbee")
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertRegex(result.stdout, rf"(?m)^code +archive {self.version}, rerun v9.9-1-gdeadbee .*: same simulator "
                                        rf"\(1 of them .*first build/paper_targets/quick/figx/result.h5: archived "
                                        rf"{self.version}, compared v9.9-1-gdeadbee\)$")
        self.assertRegex(result.stdout, rf"(?m)^OK +build/paper_targets/quick/figx/result.h5 +\(bit-identical datasets "
                                        rf"and attributes; made by {self.version}, rerun by v9.9-1-gdeadbee, the same "
                                        rf"simulator")
        self.assertRegex(result.stdout, r"(?m)^result +REPRODUCED$")
        self.assertNotIn("DIFFERENT", result.stdout)

    def test_the_simulator_hash_is_provenance_not_data(self):
        # A result whose input came from another simulator (input_simulator_sha256), its own numbers
        # bit-identical: the attribute is provenance, not compared as data (no "DIFFERENT ... attribute
        # input_simulator_sha256: archive 'aaa...', rerun 'bbb...'").
        result = self.compare_with_changed("input-build", input_simulator_sha256=OTHER_SIMULATOR)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertRegex(result.stdout, r"(?m)^OK +build/paper_targets/quick/figx/result.h5 +\(bit-identical")
        self.assertNotIn("simulator_sha256", result.stdout)
        self.assertRegex(result.stdout, r"(?m)^result +REPRODUCED$")


if __name__ == "__main__":
    unittest.main(verbosity=2)
