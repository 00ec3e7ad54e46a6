#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The Python module shockgas (python/shockgas) against files the programs write (label python).

    test_shockgas_module.py SIM MERGE ANALYZE DRIFT TAIL WORK_DIR     (DRIFT may be "none")

Each kind of file is made here with small runs (about 2 s of CPU in all) and read back:
  * a run: every snapshot's T recomputed in numpy equals the stored T(t) of its realization at its
    time; each histogram holds the whole mass N per realization; snapshots come in numeric group
    order (a run with 12 snapshot times has groups 0..11, which sort as 0, 1, 10, 11, 2 by name);
    text attributes are str;
  * a merge of two parts equals the run of all realizations at once;
  * a checkpoint (SIGINT mid-run) holds the unfinished realizations' engine states;
  * analysis results carry their input's attributes; a drift record its columns; a shockgas-tail
    output is read as a Tail (read and kind_of do not refuse it as "no kind this module knows");
  * a checkpoint's repr names it a Checkpoint, not a Run;
  * an initial condition written by write_initial_condition is run by shockgas-sim --init (and refused by crossover); what
    shockgas-sim's init reader refuses is refused when written (ValueError, no file left); an
    existing file is replaced only with overwrite=True, a shockgas run or results never; a write
    that fails leaves neither the destination nor a temporary; it carries the programs' checksums
    (Fletcher32 on every dataset, the 1.10 superblock), so that a byte changed in its data is refused
    as damaged by read_initial_condition and shockgas-sim --init (it was read and run as another start);
  * a path that does not exist raises FileNotFoundError saying so, not DamagedFile ("damaged,
    truncated or not HDF5");
  * unknown or missing schema_version, and the wrong reader for a kind, are refused by name.
"""
import os
import shutil
import signal
import subprocess
import sys
import time
import unittest
from unittest import mock

try:
    import h5py  # only to damage copies of files (schema_version) for the refusal tests
    import numpy as np
except ImportError as error:  # pragma: no cover
    print("SKIP: needs numpy and h5py (%s)" % error)
    sys.exit(77)
# python/shockgas from PYTHONPATH (ctest's): missing, the test fails rather than skips.
import shockgas  # noqa: E402

SIM, MERGE, ANALYZE, DRIFT, TAIL, WORK = sys.argv[1:7]
del sys.argv[1:7]

# T from a snapshot (numpy, plain sums) against the engine's compensated T: both are the same
# mass-weighted moments of the same doubles, so they differ by summation rounding only, a few ulp
# of T times sqrt(N) at most; 1e-12 relative is far above that and far below any real mismatch
# (another realization's or another time's T differs by percents).
T_RELATIVE_TOLERANCE = 1e-12


def run(*arguments):
    subprocess.run([str(a) for a in arguments], check=True, cwd=WORK, stdout=subprocess.DEVNULL)


def path(name):
    return os.path.join(WORK, name)


class Runs(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        os.makedirs(WORK, exist_ok=True)
        times = ",".join(str(t) for t in range(1, 13))
        common = ["-N", 1000, "-r", 0.9, "-d", 0.01, "-t", 100, "-s", 5, "--snapshot-times", times,
                  "--histogram-times", "10,100", "-j", 1, "-q"]
        run(SIM, *common, "-R", 3, "-o", path("whole.h5"))
        run(SIM, *common, "-R", 2, "-o", path("part0.h5"))
        run(SIM, *common, "-R", 1, "--first-realization", 2, "-o", path("part1.h5"))
        run(MERGE, "-o", path("merged.h5"), path("part0.h5"), path("part1.h5"))
        cls.whole = shockgas.read_run(path("whole.h5"))

    def test_shapes_and_text_attributes(self):
        r = self.whole
        self.assertEqual(r.temperature.shape, (3, len(r.time)))
        for name in ("collisions_per_particle", "clusters", "kinetic_energy"):
            self.assertEqual(getattr(r, name).shape, r.temperature.shape, name)
        self.assertEqual(r.realizations, 3)
        for name in ("status", "subthreshold", "version", "program", "engine", "snapshot_times"):
            self.assertIs(type(r.attrs[name]), str, name)
        self.assertEqual(r.attrs["status"], "complete")
        self.assertIs(type(r.attrs["particles"]), int)
        self.assertEqual(r.schema_version, 4)
        # Schema 4: the time series starts with the initial state (T(0) = 1/3 up to sampling).
        self.assertEqual(r.time[0], 0.0)
        self.assertTrue(all(r.collisions_per_particle[:, 0] == 0.0))
        # T(0) of N = 1000 uniform velocities has standard deviation sqrt((1/5 - 1/9) / 1000) = 0.0094
        # per realization; 0.03 is over 5 sigma of the 3-realization mean, and T(0) = 1 (a factor
        # 3, the paper's normalisation mistaken for ours) or 0 would fail.
        start_temperature_tolerance = 0.03
        self.assertLess(abs(r.temperature[:, 0].mean() - 1.0 / 3.0), start_temperature_tolerance)
        # Schema 3: h5py itself (not only this module) gives text as str, and
        # the numbered groups sort in time order by name (zero-padded).
        objects = list(shockgas.walk(path("whole.h5"), raw=True))  # raw: h5py's own values
        self.assertIs(type(objects[0][1]["status"]), str)
        names = [p.split("/")[2] for p, _, _ in objects if p.count("/") == 2 and p.startswith("/snapshots/")]
        self.assertEqual(names, [f"{k:02d}" for k in range(3 * 12)])  # h5py's own (name) order

    def test_snapshots_in_numeric_order_and_on_the_time_series(self):
        snapshots = self.whole.snapshots
        self.assertEqual(len(snapshots), 3 * 12)
        order = [(s.realization, s.time) for s in snapshots]
        self.assertEqual(order, sorted(order), "snapshots not in group-number order")
        for s in snapshots:
            k = int(np.flatnonzero(self.whole.time == s.time)[0])
            mass = s.mass.sum()
            mean = (s.mass * s.velocity).sum() / mass
            temperature = (s.mass * (s.velocity - mean) ** 2).sum() / mass
            stored = self.whole.temperature[s.realization, k]
            self.assertLess(abs(temperature / stored - 1), T_RELATIVE_TOLERANCE,
                            f"realization {s.realization}, t = {s.time}")
            self.assertEqual(mass, self.whole.attrs["particles"])

    def test_histograms_hold_every_particle(self):
        self.assertEqual([h.time for h in self.whole.histograms], [10.0, 100.0])
        for h in self.whole.histograms:
            self.assertEqual(h.counts.shape, (3, len(h.edges) + 1))
            np.testing.assert_array_equal(h.counts.sum(axis=1), self.whole.attrs["particles"])

    def test_merged_parts_equal_the_whole_run(self):
        merged = shockgas.read_run(path("merged.h5"))
        for name in ("time", "temperature", "clusters", "kinetic_energy", "collisions_per_particle"):
            np.testing.assert_array_equal(getattr(merged, name), getattr(self.whole, name), name)
        self.assertEqual(len(merged.snapshots), len(self.whole.snapshots))

    def test_merged_file_records_the_merge_and_keeps_the_runs_provenance(self):
        # The merged file keeps the run's provenance (its first part's program, date and host, not
        # the merge's), and merged_by, merged_date and merged_from record the merge.
        merged = shockgas.read_run(path("merged.h5")).attrs
        first = shockgas.read_run(path("part0.h5")).attrs
        for name in ("program", "version", "date", "host"):
            self.assertEqual(merged[name], first[name], name)
        self.assertEqual(merged["merged_by"], "shockgas-merge " + first["version"])
        self.assertRegex(merged["merged_date"], r"^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ$")
        version = ", shockgas " + first["version"] + ")"
        self.assertEqual(merged["merged_from"].split("\n"),
                         [path("part0.h5") + " (realizations 0 to 1" + version,
                          path("part1.h5") + " (realizations 2 to 2" + version])
        self.assertEqual(merged["simulator_sha256"], first["simulator_sha256"])

    def test_engine_switch_time(self):
        # The event engine runs one method throughout: NaN. The hybrid engine records its hand-over
        # (N = 2000, r = 0.9, delta = 1e-2: at t = 1.25^31 = 1009.74 for both realizations, as the
        # C++ test HybridEngine.FileRecordsEachRealizationsSwitchTime measures).
        self.assertTrue(np.all(np.isnan(self.whole.engine_switch_time)))
        self.assertEqual(self.whole.engine_switch_time.shape, (3,))
        run(SIM, "-N", 2000, "-r", 0.9, "-d", 0.01, "--subthreshold", "elastic", "--engine", "hybrid", "-t", 3000,
            "-R", 2, "-j", 1, "-q", "-o", path("hybrid.h5"))
        # The check times are products of 1.25 accumulated in the engine: equal to 1.25^31 to rounding.
        np.testing.assert_allclose(shockgas.read_run(path("hybrid.h5")).engine_switch_time, [1.25 ** 31] * 2,
                                   rtol=T_RELATIVE_TOLERANCE)
        # A file from before the record: no dataset, NaN as the C++ reader gives.
        old = path("before_switch_record.h5")
        shutil.copyfile(path("hybrid.h5"), old)
        with h5py.File(old, "r+") as handle:
            del handle["timeseries/engine_switch_time"]
        self.assertTrue(np.all(np.isnan(shockgas.read_run(old).engine_switch_time)))

    def test_results_carry_their_input(self):
        run(ANALYZE, "decay", path("whole.h5"), "-o", path("decay.h5"), "--data-only", "--data", path("T.dat"))
        run(ANALYZE, "shocks", path("whole.h5"), "-o", path("shocks.h5"))
        results = shockgas.read(path("shocks.h5"))
        self.assertIsInstance(results, shockgas.Results)
        self.assertTrue(results.sections, "no result sections")
        (inputs,) = results.inputs()
        self.assertEqual(inputs["seed"], self.whole.attrs["seed"])
        self.assertEqual(inputs["path"], path("whole.h5"))
        self.assertIs(type(results.attrs["program"]), str)


class OtherKinds(unittest.TestCase):
    def test_checkpoint_of_an_interrupted_run(self):
        target = path("long.h5")
        for stale in (target, target + ".checkpoint"):
            if os.path.exists(stale):
                os.remove(stale)
        process = subprocess.Popen([SIM, "-N", "100000", "-r", "0.9", "-d", "0.01", "-t", "1e6", "-R", "2",
                                    "-j", "2", "-q", "-o", target], cwd=WORK, stderr=subprocess.DEVNULL)
        time.sleep(1.5)  # into the run: the realizations are under way, none can finish
        process.send_signal(signal.SIGINT)
        process.wait(timeout=60)
        checkpoint = shockgas.read_checkpoint(target + ".checkpoint")
        self.assertIsInstance(checkpoint, shockgas.Checkpoint)
        self.assertEqual(checkpoint.attrs["status"], "checkpoint")
        in_progress = np.flatnonzero(checkpoint.realization_status == 4)
        self.assertEqual(sorted(checkpoint.engines), sorted(int(k) for k in in_progress))
        self.assertTrue(checkpoint.engines, "no engine state in the checkpoint")
        for state in checkpoint.engines.values():
            self.assertIs(type(state.attrs["kind"]), str)
        self.assertEqual(len(checkpoint.samples_done), checkpoint.realizations)
        self.assertIn("R=2", checkpoint.signature)
        self.assertTrue(repr(checkpoint).startswith("<Checkpoint "), repr(checkpoint))
        self.assertTrue(repr(shockgas.read_run(target)).startswith("<Run "))
        self.assertEqual(shockgas.read_run(target).attrs["status"], "interrupted")

    @unittest.skipIf(DRIFT == "none", "shockgas-drift not built (SHOCKGAS_BUILD_BENCH=OFF)")
    def test_drift_record(self):
        run(DRIFT, "-N", 100, "-r", 0.5, "-d", 0.01, "--subthreshold", "elastic", "-s", 1, "-c", 1e5,
            "--record-every", 2e4, "-o", path("drift.h5"))
        drift = shockgas.read_drift(path("drift.h5"))
        lengths = {len(column) for column in drift.columns.values()}
        self.assertEqual(len(lengths), 1, "columns of different lengths")
        self.assertGreaterEqual(lengths.pop(), 5)

    def test_tail_file(self):
        # shockgas-tail, a tiny ladder (3 biases x 2 chains x 10 steps: < 0.1 s): read as a Tail.
        target = path("tail.h5")
        if os.path.exists(target):
            os.remove(target)
        run(TAIL, "-t", 10, "--half-window", 20, "--steps-per-bias", 10, "--burn-in", 0, "--chains", 2,
            "--biases", 0, 1, 2, "-j", 1, "-o", target)
        self.assertEqual(shockgas.kind_of(target), "tail")
        tail = shockgas.read(target)
        self.assertIsInstance(tail, shockgas.Tail)
        self.assertIs(type(shockgas.read_tail(target)), shockgas.Tail)
        self.assertEqual(tail.attrs["program"], "shockgas-tail")
        self.assertEqual(tail.attrs["time"], 10.0)
        # Bins of 0.02 over [z_min, z_max] = [-3, 7] (the defaults): 500, one value each.
        self.assertEqual(len(tail.z), 500)
        for name in ("phi", "phi_sigma", "log_phi", "log_phi_sigma", "samples"):
            self.assertEqual(getattr(tail, name).shape, tail.z.shape, name)
        self.assertEqual(tail.log_phi_leave_one_chain_out.shape, (2, 500))
        np.testing.assert_array_equal(tail.pieces.bias, [0.0, 1.0, 2.0])
        self.assertTrue(repr(tail).startswith("<Tail "), repr(tail))
        with self.assertRaisesRegex(shockgas.SchemaError, "read it with shockgas.read_tail"):
            shockgas.read_run(target)

    def test_missing_file_is_not_called_damaged(self):
        missing = path("no_such_run.h5")
        for reader in (shockgas.read, shockgas.read_run, shockgas.read_results, shockgas.attributes, shockgas.kind_of):
            with self.assertRaises(FileNotFoundError) as raised:
                reader(missing)
            self.assertNotIsInstance(raised.exception, shockgas.DamagedFile, reader.__name__)
            self.assertIn("does not exist", str(raised.exception))
            self.assertIn("no_such_run.h5", str(raised.exception))
            self.assertNotIn("damaged", str(raised.exception))
        with self.assertRaises(IsADirectoryError):
            shockgas.read(WORK)

    def test_initial_condition_round_trip(self):
        n = 50
        position = np.arange(n) * 2.0
        velocity = np.linspace(-1, 1, n)
        shockgas.write_initial_condition(path("start.h5"), position, velocity, ring_length=2.0 * n, overwrite=True)
        run(SIM, "--init", path("start.h5"), "-t", 10, "-q", "-o", path("from_start.h5"))
        started = shockgas.read_run(path("from_start.h5"))
        self.assertEqual(started.attrs["particles"], n)
        self.assertEqual(started.attrs["ring_length"], 2.0 * n)
        # crossover knows T0 and Haff's constant of the drawn starts only: such a run is refused, named.
        refused = subprocess.run([ANALYZE, "crossover", path("from_start.h5"), path("from_start.h5"), "-o",
                                  path("init_crossover.h5")], cwd=WORK, capture_output=True, text=True)
        self.assertEqual(refused.returncode, 2, refused.stderr)
        self.assertIn("starts from the initial-condition file", refused.stderr)
        self.assertFalse(os.path.exists(path("init_crossover.h5")))

    def test_initial_condition_carries_checksums(self):
        # As every file shockgas-sim writes (sim/io/src/h5.cpp): the HDF5 1.10 format, whose metadata
        # carry checksums, and every dataset chunked with Fletcher32. A byte changed in the data is
        # then refused by both readers, named damaged, never read as another start.
        n = 40
        position, velocity, mass = np.arange(n) * 0.5 + 0.125, np.linspace(-1, 1, n), np.linspace(1, 2, n)
        start = path("checksummed_start.h5")
        shockgas.write_initial_condition(start, position, velocity, mass=mass, ring_length=0.5 * n, overwrite=True)
        with shockgas.open_file(start, check_schema=False) as handle:
            for name in ("position", "velocity", "mass"):
                self.assertTrue(handle[name].fletcher32, f"{name}: no Fletcher32 checksum")
        with open(start, "rb") as handle, open(path("whole.h5"), "rb") as run_file:
            superblock_version = handle.read(9)[8]
            self.assertEqual(superblock_version, run_file.read(9)[8], "not the superblock shockgas-sim writes")
        with open(start, "rb") as handle:
            raw = bytearray(handle.read())
        where = raw.find(position.tobytes())
        self.assertGreater(where, 0)
        raw[where + 8 * 3] ^= 0x01  # the last bit of position[3]'s mantissa
        damaged = path("damaged_start.h5")
        with open(damaged, "wb") as handle:
            handle.write(raw)
        with self.assertRaisesRegex(shockgas.DamagedFile, "position"):
            shockgas.read_initial_condition(damaged)
        refused = subprocess.run([SIM, "--init", damaged, "-t", "1", "-q", "-o", path("never.h5")], cwd=WORK,
                                 capture_output=True, text=True)
        self.assertEqual(refused.returncode, 2, refused.stderr)
        self.assertIn("damaged", refused.stderr)
        self.assertFalse(os.path.exists(path("never.h5")))

    def leftovers(self):
        return sorted(name for name in os.listdir(WORK) if ".tmp." in name)

    def test_initial_condition_refused_as_shockgas_sim_refuses_it(self):
        # Each start below is one shockgas-sim's init reader refuses (sim/model/src/state.cpp, validate):
        # write_initial_condition refuses it too, with the same words, and leaves no file.
        ok = dict(position=[0.0, 1.0, 2.0], velocity=[0.1, -0.2, 0.3])
        cases = {
            "need at least 2 particles": dict(position=[0.0], velocity=[0.1]),
            "velocity has 2 values but position has 3": dict(ok, velocity=[0.1, 0.2]),
            "mass has 2 values but position has 3": dict(ok, mass=[1.0, 1.0]),
            "position\\[1\\] is not finite": dict(ok, position=[0.0, np.nan, 2.0]),
            "velocity\\[2\\] is not finite": dict(ok, velocity=[0.1, 0.2, np.inf]),
            "mass\\[0\\] must be positive": dict(ok, mass=[0.0, 1.0, 1.0]),
            "position\\[2\\] = 3.0 lies outside": dict(ok, position=[0.0, 1.0, 3.0]),
            "position\\[0\\] = -0.5 lies outside": dict(ok, position=[-0.5, 1.0, 2.0]),
            "positions are not sorted": dict(ok, position=[0.0, 2.0, 1.0]),
            "ring_length must be positive": dict(ok, ring_length=-3.0),
        }
        target = path("refused_start.h5")
        for words, arguments in cases.items():
            with self.subTest(words):
                if os.path.exists(target):
                    os.remove(target)
                with self.assertRaisesRegex(ValueError, words):
                    shockgas.write_initial_condition(target, **arguments)
                self.assertFalse(os.path.exists(target))
        # And the same starts written raw (h5py) are refused by shockgas-sim, exit status 2: the
        # rules are the simulator's, not stricter.
        for words, arguments in list(cases.items())[1:4]:
            with h5py.File(target, "w") as handle:
                handle.attrs["ring_length"] = float(arguments.get("ring_length", 3.0))
                for name in ("position", "velocity", "mass"):
                    if name in arguments:
                        handle[name] = np.asarray(arguments[name], dtype=float)
            refused = subprocess.run([SIM, "--init", target, "-t", "1", "-q", "-o", path("never.h5")], cwd=WORK,
                                     capture_output=True, text=True)
            self.assertEqual(refused.returncode, 2, words + ": " + refused.stderr)
        os.remove(target)
        self.assertEqual(self.leftovers(), [])

    def test_initial_condition_never_replaces_a_run_and_replaces_a_start_only_when_asked(self):
        start = path("replace_start.h5")
        if os.path.exists(start):
            os.remove(start)
        shockgas.write_initial_condition(start, [0.0, 1.0], [0.5, -0.5])
        with self.assertRaisesRegex(FileExistsError, "overwrite=True"):
            shockgas.write_initial_condition(start, [0.0, 1.0, 2.0], [0.5, -0.5, 0.0])
        with shockgas.open_file(start, check_schema=False) as handle:
            self.assertEqual(len(handle["position"]), 2)  # untouched
        shockgas.write_initial_condition(start, [0.0, 1.0, 2.0], [0.5, -0.5, 0.0], overwrite=True)
        with shockgas.open_file(start, check_schema=False) as handle:
            self.assertEqual(len(handle["position"]), 3)
        # A run (and results) is never replaced, overwrite=True or not.
        with open(path("whole.h5"), "rb") as handle:
            before = handle.read()
        for overwrite in (False, True):
            with self.assertRaisesRegex(FileExistsError, "shockgas-sim"):
                shockgas.write_initial_condition(path("whole.h5"), [0.0, 1.0], [0.5, -0.5], overwrite=overwrite)
        with open(path("whole.h5"), "rb") as handle:
            self.assertEqual(handle.read(), before)
        # Nor a directory.
        os.makedirs(path("a_directory.h5"), exist_ok=True)
        with self.assertRaises(FileExistsError):
            shockgas.write_initial_condition(path("a_directory.h5"), [0.0, 1.0], [0.5, -0.5], overwrite=True)
        self.assertEqual(self.leftovers(), [])

    def test_initial_condition_write_that_fails_leaves_nothing(self):
        target = path("failed_start.h5")
        if os.path.exists(target):
            os.remove(target)
        full = OSError(28, "No space left on device")
        for step in ("link", "replace"):  # the last step of a new file, of a replacement
            with self.subTest(step), mock.patch.object(shockgas.files.os, step, side_effect=full):
                if step == "replace":
                    shockgas.write_initial_condition(target, [0.0, 1.0], [0.5, -0.5])
                with self.assertRaises(OSError):
                    shockgas.write_initial_condition(target, [0.0, 1.0, 2.0], [0.5, -0.5, 0.0],
                                                     overwrite=(step == "replace"))
                self.assertEqual(self.leftovers(), [])
                if step == "link":
                    self.assertFalse(os.path.exists(target))
                else:  # the old start is still there, whole
                    with shockgas.open_file(target, check_schema=False) as handle:
                        self.assertEqual(len(handle["position"]), 2)


class Refusals(unittest.TestCase):
    def copy_with(self, name, change):
        copy = path(name)
        shutil.copyfile(path("whole.h5"), copy)
        with h5py.File(copy, "r+") as handle:
            change(handle.attrs)
        return copy

    def test_unknown_schema_version(self):
        newer = self.copy_with("newer.h5", lambda attrs: attrs.__setitem__("schema_version", 99))
        with self.assertRaises(shockgas.UnsupportedSchemaVersion) as raised:
            shockgas.read_run(newer)
        message = str(raised.exception)
        for needed in ("newer.h5", "schema_version 99", "(1, 2, 3, 4)", "newer than this module"):
            self.assertIn(needed, message)
        with self.assertRaises(shockgas.UnsupportedSchemaVersion):
            shockgas.attributes(newer)

    def test_missing_schema_version(self):
        bare = self.copy_with("bare.h5", lambda attrs: attrs.__delitem__("schema_version"))
        with self.assertRaisesRegex(shockgas.SchemaError, "not a file written by shockgas"):
            shockgas.read(bare)

    def test_wrong_reader_names_the_right_one(self):
        with self.assertRaisesRegex(shockgas.SchemaError, "read it with shockgas.read_run"):
            shockgas.read_results(path("whole.h5"))


if __name__ == "__main__":
    loader = unittest.TestLoader()
    suite = unittest.TestSuite([loader.loadTestsFromTestCase(c) for c in (Runs, OtherKinds, Refusals)])
    sys.exit(0 if unittest.TextTestRunner(verbosity=2).run(suite).wasSuccessful() else 1)
