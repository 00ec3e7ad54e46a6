#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""tools/tail_against_exact.py on small shockgas-tail runs (ctest python.tail_against_exact, label
python; about 25 s of CPU, most of it the exact Phi's quadrature).

    test_tail_against_exact_cli.py TAIL WORK_DIR

  * a Gaussian start prints measured/exact and no EB13 column; a uniform start prints the EB13 shift
    (python/exact_ballistic.py, uniform_start_log_phi_shift) and the ratio against the shifted Phi;
  * beyond z = t^(1/3) no uniform window can reach, so the shift is -inf and the ratio '-';
  * a missing file or a --z that is not numbers: exit 2, one line.
"""
import math
import os
import unittest

import script_checks as sc

sc.require("h5py", "numpy", "scipy")

TAIL, WORK = sc.arguments(2)
TOOL = sc.script("tools", "tail_against_exact.py")
NAME = "tail_against_exact.py"
import exact_ballistic as eb  # noqa: E402


def sample(law, name):
    os.makedirs(WORK, exist_ok=True)
    result = sc.run([TAIL, "-t", 100, "--half-window", 150, "--focus", 100, "--z-reach", 1, "--z-step", 0.5,
                     "--steps-per-bias", 300, "--burn-in", 30, "--chains", 2, "--seed", 4, "-j", 1,
                     "--velocity-law", law, "-o", name], cwd=WORK)
    assert result.returncode == 0, result.stderr
    return os.path.join(WORK, name)


def table(result):
    return [line.split() for line in result.stdout.splitlines() if not line.startswith("#")]


class Columns(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.gaussian, cls.uniform = sample("gaussian", "gaussian.h5"), sample("uniform", "uniform.h5")

    def test_gaussian_has_no_shift(self):
        result = sc.run([sc.PYTHON, TOOL, self.gaussian, "--z", "0,1"])
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("velocity law gaussian", result.stdout)
        rows = table(result)
        self.assertEqual([len(r) for r in rows], [4, 4])

    def test_uniform_prints_the_eb13_shift(self):
        result = sc.run([sc.PYTHON, TOOL, self.uniform, "--z", "1,5"])
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("velocity law uniform", result.stdout)
        first, beyond = table(result)
        z = float(first[0])
        self.assertAlmostEqual(float(first[4]), eb.uniform_start_log_phi_shift(z, 100.0) / math.log(10.0), places=3)
        # measured/(exact*shift) = (measured/exact) / 10^shift, to the printed digits
        self.assertAlmostEqual(float(first[5]) / (float(first[2]) / 10.0 ** float(first[4])), 1.0, delta=0.01)
        self.assertEqual(beyond[4:], ["-inf", "-"])  # z = 5 > 100^(1/3) = 4.64


class Refusals(unittest.TestCase):
    def test_missing_file(self):
        sc.one_line_error(self, sc.run([sc.PYTHON, TOOL, os.path.join(WORK, "none.h5")]), NAME, "none.h5")

    def test_bad_z(self):
        result = sc.run([sc.PYTHON, TOOL, os.path.join(WORK, "none.h5"), "--z", "1,a"])
        self.assertEqual(result.returncode, 2)
        self.assertIn("--z needs comma-separated numbers", result.stderr)


if __name__ == "__main__":
    unittest.main()
