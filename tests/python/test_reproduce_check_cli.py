#!/usr/bin/python3
"""tools/reproduce-check on archives it cannot read: exit 2, one line, no temporary left behind
(ctest python.reproduce_check_unreadable, label python; < 1 s).

    test_reproduce_check_cli.py WORK_DIR

docs/archive.md gives exit status 1 the meaning NOT REPRODUCED and 2 an unreadable archive. A missing
archive or a file that is not one gave a Python traceback and exit status 1, and every early exit
left its temporary work directory (/tmp/shockgas-check-*) behind. Each case below runs the tool with
TMPDIR set to an empty directory of its own, and asserts exit status 2, one stderr line
"reproduce-check: error: ..." naming what is wrong, and that directory empty afterwards: a missing
archive, a text file, a gzip file that is not a tar archive, a tar.gz cut short, a tar.gz without
MANIFEST, one whose MANIFEST is not JSON, one whose MANIFEST lacks the fields, and a directory
holding no archive.
"""
import gzip
import io
import json
import os
import shutil
import sys
import tarfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
import script_checks as sc  # noqa: E402

sc.require("h5py", "numpy")

WORK = sc.arguments(1)
TOOL = sc.script("tools", "reproduce-check")
NAME = "reproduce-check"


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


if __name__ == "__main__":
    unittest.main(verbosity=2)
