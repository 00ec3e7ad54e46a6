#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Reads a shockgas-tail estimate of Phi against the exact sticky-gas Phi (python/exact_ballistic.py).

    /usr/bin/python3 tools/tail_against_exact.py TAIL.h5 [--z 1,2,3,4,5,5.5,6,6.5]

For each z it prints the output bin whose centre is nearest, the exact Phi at that centre, the
measured Phi over the exact one with the sigma of log10 Phi, and, for a run from the uniform start
(`--velocity-law uniform`), the exact Phi shifted by EB13 (the uniform law's finite-t correction at
first order, which bounds the true shift from above) and the measured Phi over that. The tables of
docs/far-tail.md were read off with it. Exit code 2 with one line on a file it cannot read.
"""
import argparse
import sys

import numpy as np

import shockgas_path  # noqa: F401  (python/ of this source tree on Python's path: tools/shockgas_path.py)
import exact_ballistic as eb
import shockgas


def rows(tail, zs):
    """(z bin centre, exact Phi, measured/exact, sigma log10, EB13 shift in log10 or None, measured/shifted)."""
    uniform = str(tail.attrs.get("velocity_law")) == "uniform"
    time = float(tail.attrs["time"])
    bins = [int(np.argmin(np.abs(tail.z - z))) for z in zs]
    exacts = eb.phi(np.array([tail.z[i] for i in bins]))  # one call: each builds the quadrature grid
    out = []
    for i, exact in zip(bins, exacts):
        centre, exact = float(tail.z[i]), float(exact)
        ratio = float(tail.phi[i]) / exact if tail.samples[i] > 0 else float("nan")
        sigma = float(tail.log_phi_sigma[i]) / np.log(10.0)
        shift = eb.uniform_start_log_phi_shift(centre, time) / np.log(10.0) if uniform else None
        shifted = ratio / 10.0 ** shift if uniform and np.isfinite(shift) else None
        out.append((centre, exact, ratio, sigma, shift, shifted))
    return out, uniform, time


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("tail", help="a shockgas-tail output file")
    parser.add_argument("--z", default="1,2,3,4,4.5,5,5.5,6,6.5", help="comma-separated z (default: %(default)s)")
    args = parser.parse_args(argv)
    try:
        zs = [float(v) for v in args.z.split(",")]
    except ValueError:
        parser.error("--z needs comma-separated numbers, not '%s'" % args.z)
    try:
        tail = shockgas.read_tail(args.tail)
    except (OSError, shockgas.SchemaError, ValueError, KeyError) as error:
        print("tail_against_exact.py: error: cannot read '%s': %s" % (args.tail, error), file=sys.stderr)
        return 2
    table, uniform, time = rows(tail, zs)
    print("# %s: t = %g, velocity law %s" % (args.tail, time, "uniform" if uniform else "gaussian"))
    header = "# z_bin  exact_phi  measured/exact  sigma_log10"
    print(header + ("  EB13_shift_log10  measured/(exact*shift)" if uniform else ""))
    for centre, exact, ratio, sigma, shift, shifted in table:
        line = "%6.3f  %.3e  %.3g  %.2f" % (centre, exact, ratio, sigma)
        if uniform:
            line += "  %.3f  %s" % (shift, "%.3g" % shifted if shifted is not None else "-")
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
