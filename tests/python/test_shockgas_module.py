#!/usr/bin/python3
"""The Python module shockgas (python/shockgas) against files the programs write (label python).

    test_shockgas_module.py SIM MERGE ANALYZE DRIFT WORK_DIR     (DRIFT may be "none")

Each kind of file is made here with small runs (about 2 s of CPU in all) and read back:
  * a run: every snapshot's T recomputed in numpy equals the stored T(t) of its realization at its
    time; each histogram holds the whole mass N per realization; snapshots come in numeric group
    order (a run with 12 snapshot times has groups 0..11, which sort as 0, 1, 10, 11, 2 by name);
    text attributes are str;
  * a merge of two parts equals the run of all realizations at once;
  * a checkpoint (SIGINT mid-run) holds the unfinished realizations' engine states;
  * analysis results carry their input's attributes; a drift record its columns;
  * an initial condition written by write_initial_condition is run by shockgas-sim --init;
  * unknown or missing schema_version, and the wrong reader for a kind, are refused by name.
"""
import os
import shutil
import signal
import subprocess
import sys
import time
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", "..", "python"))
try:
    import h5py  # only to damage copies of files (schema_version) for the refusal tests
    import numpy as np

    import shockgas
except ImportError as error:  # pragma: no cover
    print("SKIP: needs numpy and h5py (%s)" % error)
    sys.exit(77)

SIM, MERGE, ANALYZE, DRIFT, WORK = sys.argv[1:6]
del sys.argv[1:6]

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
        self.assertEqual(shockgas.read_run(target).attrs["status"], "interrupted")

    @unittest.skipIf(DRIFT == "none", "shockgas-drift not built (SHOCKGAS_BUILD_BENCH=OFF)")
    def test_drift_record(self):
        run(DRIFT, "-N", 100, "-r", 0.5, "-d", 0.01, "--subthreshold", "elastic", "-s", 1, "-c", 1e5,
            "--record-every", 2e4, "-o", path("drift.h5"))
        drift = shockgas.read_drift(path("drift.h5"))
        lengths = {len(column) for column in drift.columns.values()}
        self.assertEqual(len(lengths), 1, "columns of different lengths")
        self.assertGreaterEqual(lengths.pop(), 5)

    def test_initial_condition_round_trip(self):
        n = 50
        position = np.arange(n) * 2.0
        velocity = np.linspace(-1, 1, n)
        shockgas.write_initial_condition(path("start.h5"), position, velocity, ring_length=2.0 * n)
        run(SIM, "--init", path("start.h5"), "-t", 10, "-q", "-o", path("from_start.h5"))
        started = shockgas.read_run(path("from_start.h5"))
        self.assertEqual(started.attrs["particles"], n)
        self.assertEqual(started.attrs["ring_length"], 2.0 * n)


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
