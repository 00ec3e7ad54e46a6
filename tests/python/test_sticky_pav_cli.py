#!/usr/bin/python3
"""python/sticky_pav.py's ensemble comparison on small inputs (ctest python.sticky_pav_inputs, label
python; about 7 s of CPU, most of it the exact theory's constants).

    test_sticky_pav_cli.py WORK_DIR

  * --hist-dir with a time below ~55: the mass bins (M_EDGES moved to half-integer masses) number
    fewer at t = 10 than at t = 100, and the per-realization histograms were stacked into one array
    (ValueError: inhomogeneous shape). Now each time has its own: the files for t = 10 and t = 100
    are written, with fewer bins at t = 10.
  * N = 2000, 2 realizations (seed 3): in some bins of F(m) every realization holds the same number
    of clusters, a standard error of 0 (and in m F(m), one of rounding size): chi2 printed "inf" (and
    5.6e28). Those bins are left out and counted ("left out, no spread ..."); every chi2 is finite.
  * --compare with one or two --times fitted r_inf + a t^(-1/3) with "dof -1" (or 0) and errors of
    1e6: refused, exit 2, one line; so are one realization with --compare, a time the periodic copies
    cannot reach (a traceback before; the line names the --copies needed) and a time <= 0.
"""
import math
import os
import re
import shutil
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
import script_checks as sc  # noqa: E402

try:
    import numpy  # noqa: F401
    import scipy  # noqa: F401
except ImportError as error:  # pragma: no cover
    print("SKIP: needs numpy and scipy (%s)" % error)
    sys.exit(77)

WORK = sys.argv[1]
del sys.argv[1]
TOOL = sc.script("python", "sticky_pav.py")
NAME = "sticky_pav.py"
# Every chi2 printed must be finite and below this. A bin kept with an error bar of rounding size
# (1e-16 relative) gave 5.6e28 in this very case, a bin with none "inf"; the largest honest value
# here is 5.9e4 (m F(m) at t = 800: with 2 realizations an error bar is one difference, and a
# difference of one cluster's mass makes it small by chance).
CHI2_CEILING = 1e6


def pav(*arguments):
    return sc.run([sc.PYTHON, TOOL, *arguments], cwd=WORK)


class Histograms(unittest.TestCase):
    def test_small_times_and_bins_without_spread(self):
        hist = os.path.join(WORK, "hist")
        shutil.rmtree(hist, ignore_errors=True)
        result = pav("--N", 2000, "--realizations", 2, "--seed", 3, "--times", 10, 100, 200, 400, 800,
                     "--compare", "--hist-dir", hist)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr[-3000:])
        lines = [line for line in result.stdout.splitlines() if line.startswith("# t = ")]
        self.assertEqual(len(lines), 5, result.stdout)
        for line in lines:
            values = re.findall(r"(\S+)/(\d+)", line)
            self.assertEqual(len(values), 4, line)  # Phi, F(m), F(m) without its first bin, m F(m)
            for chi2, bins in values:
                self.assertNotEqual(chi2, "n/a", line)
                self.assertTrue(math.isfinite(float(chi2)) and float(chi2) < CHI2_CEILING, line)
                self.assertGreater(int(bins), 0, line)
        self.assertTrue(any("left out, no spread over the 2 realizations" in line for line in lines), result.stdout)

        def bins(name):
            with open(os.path.join(hist, name)) as handle:
                return sum(1 for line in handle if not line.startswith("#"))
        self.assertLess(bins("mass_number_t10.dat"), bins("mass_number_t100.dat"))
        self.assertEqual(bins("phi_t10.dat"), bins("phi_t100.dat"))  # z bins do not depend on t


class Refusals(unittest.TestCase):
    def test_a_fit_needs_three_times(self):
        for times in ([100], [100, 200], [100, 100, 200]):
            sc.one_line_error(self, pav("--N", 2000, "--realizations", 3, "--times", *times, "--compare"), NAME,
                              "3 or more different --times")

    def test_compare_needs_two_realizations(self):
        sc.one_line_error(self, pav("--N", 2000, "--realizations", 1, "--times", 100, 200, 300, "--compare"), NAME,
                          "--realizations 2 or more")

    def test_a_time_past_the_copies(self):
        # N = 2000 on a ring of L = 2000: t = 1e5 needs copies > 2 t max|v| / L = 100 max|v|, and
        # max|v| of 2000 uniform velocities on [-1, 1] less their mean lies in [0.99, 1.05]
        # (the mean of 2000 is within +-0.05 at 3.8 sigma): 100 to 106 copies.
        line = sc.one_line_error(self, pav("--N", 2000, "--realizations", 2, "--times", 100, 100000), NAME,
                                 "t = 100000 too large for 1 copies", "--copies")
        needed = int(re.search(r"--copies (\d+) or more", line).group(1))
        self.assertTrue(100 <= needed <= 106, line)

    def test_times_must_be_positive(self):
        sc.one_line_error(self, pav("--N", 2000, "--times", 0, 100), NAME, "> 0")


if __name__ == "__main__":
    os.makedirs(WORK, exist_ok=True)
    unittest.main(verbosity=2)
