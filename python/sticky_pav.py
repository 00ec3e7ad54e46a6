#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Exact state of a sticky gas (r = 0) at any time t, without events, by isotonic regression.

Run with Debian's interpreter (numpy):
    /usr/bin/python3 python/sticky_pav.py --N 1000000 --realizations 5 --seed 1 \
        --times 100 215.4 464.2 1000 2154 4642 10000 --compare

Method (generalized variational principle: E, Rykov & Sinai, CMP 177, 349 (1996); Brenier &
Grenier, SIAM J. Numer. Anal. 35, 2317 (1998)).  On a line, the clusters of the sticky gas at time t
are the level sets of the weighted isotonic (non-decreasing) regression of
        y_i = x_i + t v_i            with weights m_i,
i.e. the faces of the convex minorant of the cumulative sum of m_i y_i against cumulative mass.
A cluster's position is the block's mass-weighted mean of y, its velocity = momentum / mass.

Isotonic regression is done with a vectorised pool-adjacent-violators: every maximal run of
adjacent blocks whose means strictly decrease is pooled at once (a run of violators always
ends up in one block: pooling a violating pair keeps its mean >= the next block's), and this is
repeated until the means are non-decreasing.  The solution is unique, so the order of pooling
does not matter.  Typically ~10-15 sweeps.  Clusters never split, so for an increasing list
of times the blocks at t_k are used as the starting blocks at t_{k+1} (exact).

Ring of length L: the centre-of-mass frame is used (total momentum 0), and the ring is unrolled
into 2*copies+1 periodic copies; each physical cluster is taken once, as the image whose first
(leftmost) particle lies in the central copy.  Information travels at most at speed
2 max|v| (relative), so copies = 1 is exact while 2 t max|v| < L; this is asserted (a later time is
refused with the --copies it needs).

--compare prints, per time, T t^(2/3)/kappa, n t^(2/3)/nu and the kurtosis of Phi, each the mean over
the realizations +- its standard error from their spread (2 or more realizations), and fits
ratio(t) = r_inf + a t^(-1/3) to the first two over 3 or more times, weighted by those errors. The
fit needs MIN_FIT_REALIZATIONS (5) realizations or more; with fewer it is printed "n/a (...)", the
table (and --hist-dir) as usual. With R realizations a point's (mean - fit)/error is Student's t
with R - 1 degrees of freedom, whose square has no finite mean for R <= 3: for a true model at the
7 default times (20000 Gaussian trials) chi2/dof had median 2.8, mean 8.9 and 1% above 100 with
R = 2, median 1.15 and 99% below 6.5 with R = 5; and where two realizations held the same number of
clusters the error was 0 and the fit died (LinAlgError). Counting errors, which serve --hist-dir
below, do not serve here: the clusters of one ring are correlated (their masses add up to N), and
over realizations the variance of the cluster count is 0.37 to 0.44 of its Poisson value, that of
T 1.2 to 1.35 times the one of independent clusters (N = 2000 and 20000, 300 to 1000 realizations,
t = 100 to 800). A time at which every realization holds the same value (the same count at small
N, or no collision yet) has no error bar either: that fit is n/a, naming the time.
The +- of r_inf and a is the delete-one jackknife over the realizations (the fit redone without
each, its weights kept), the project's error bar (analysis/README.md). The fit's own widths, also
printed, take the times as independent, but one realization's values at different times are
correlated (its clusters only merge), and came out too small: at N = 2000, R = 10, 9 times from 10
to 400, over five sets of 100 ensembles (seeds fixed), the fit's sigma of r_inf was 0.48 to 0.62 of
the spread of r_inf over the ensembles (one-sigma coverage 0.37 to 0.50), the jackknife's 0.82 to
1.05 (coverage 0.58 to 0.69). chi2/dof, from the same independence, describes the shape only.

--hist-dir prints, per time, chi2/bins of the realizations' mean histogram (Phi(z), F(m), m F(m))
against the exact theory's bin averages, each bin's error bar the counting error of that mean: a
cluster is one count of weight its mass (Phi, m F(m)) or 1 (F(m)), so a bin's variance is the sum of
its clusters' squared weights over all realizations, divided by R^2 (compound Poisson). It holds for
any number of realizations, 2 as well as 40, because each realization holds many nearly independent
clusters: measured, the realizations' own scatter is 0.8 to 1.05 of this variance (N = 2000 and
20000, 20 to 40 realizations, t = 100 to 1000). Error bars from that scatter, per bin, would not do:
with two realizations (mean - theory)/error is then Student's t with one degree of freedom (a Cauchy
law), and chi2/bins of Phi at t = 100 to 800 (N = 20000, 200 pairs of seeds) comes out 9 to 3000,
median 93; with counting errors it is 0.6 to 2.3, median 1.01. With weights as broad as the masses
and few clusters per bin it runs ~10% high (a bin's squared weights are estimated from its own
clusters). Bins holding fewer than MIN_BIN_CLUSTERS clusters over all realizations are left out;
"n/a/0" when no bin is left. The theory is the t -> infinity limit: at small t, F(m) lies many error
bars off it (the cluster count approaches nu slowly), the first bin, m < 0.1, most (also given
without it); with many realizations finite-t corrections begin to show in Phi too (chi2/bins 0.8 to
1.8 with 40). The mass bins depend on t, so each time has its own.

--init FILE runs one start given as text, a line 'x v [m]' per particle ('#' comments, an optional
'# L = <ring length>' line), or as shockgas-sim's HDF5 --init file (shockgas.read_initial_condition);
every x must lie on the ring [0, L). Positions outside [0, L) and a file holding no particle are
refused by name.

A user's mistake is one line "sticky_pav.py: error: ..." on stderr and exit status 2
(python/shockgas/cli.py; where the shockgas module is out of reach, argparse's usage block comes
above that line). That includes an output (--clusters-out, --json, --hist-dir) that cannot be
written, checked before the work (a missing directory, a file in the way, no permission, a
read-only file system) and when written (a full disk). Each output file is written beside its
destination and renamed onto it once whole (shockgas.cli.atomic_output): a failure or Ctrl-C leaves
the previous file as it was.
"""
import contextlib
import json
import os
import sys
import time
import warnings

try:
    import numpy as np
except ImportError as error:  # pragma: no cover - depends on the machine
    print("sticky_pav.py: error: %s is missing: run it with Debian's /usr/bin/python3 (python3-numpy, "
          "python3-scipy)" % (error.name or error), file=sys.stderr)
    sys.exit(2)
try:  # one-line refusals, exit status 2 (python/shockgas/cli.py, the project's one place for them)
    from shockgas.cli import (ArgumentParser, atomic_output, cannot_write, output_directory_problem,
                              output_file_problem)
except ImportError:
    # This solver needs numpy alone, and is installed beside exact_ballistic.py in share/shockgas/python,
    # where the shockgas module (numpy and h5py) is not on Python's path for every prefix: it then runs
    # all the same, with argparse's usage block above the error line, an output that cannot be
    # written is found when it is written (after the work) rather than before, and outputs are
    # written in place (open), not beside and renamed.
    from argparse import ArgumentParser

    def atomic_output(path, mode="w"):
        return open(path, mode)

    def output_file_problem(path):
        return None

    output_directory_problem = output_file_problem

    def cannot_write(path, cause, option=None):
        return "cannot write %s'%s': %s" % (option + " " if option else "", path,
                                           getattr(cause, "strerror", None) or cause)


# ----------------------------------------------------------------------------------------------
# initial conditions
# ----------------------------------------------------------------------------------------------
def generate_initial(N, seed, L=None, vmax=1.0):
    """Equally spaced unit masses (spacing L/N, default 1), velocities i.i.d. U[-vmax, vmax]."""
    L = float(N) if L is None else float(L)
    rng = np.random.default_rng(seed)
    x = np.arange(N, dtype=float) * (L / N)
    v = rng.uniform(-vmax, vmax, size=N)
    m = np.ones(N)
    return x, v, m, L


def read_initial(path, L=None):
    """Whitespace columns 'x v [m]' ('#' comments).  L from argument or a '# L = <value>' line,
    else N * (mean spacing). Or shockgas-sim's HDF5 --init format (shockgas.read_initial_condition),
    whose ring_length is L (an argument L that differs is a ValueError). A file holding no particle
    line (empty, or comments alone) and a ring length that is not finite and > 0 are ValueError."""
    try:
        import h5py
    except ImportError:  # no HDF5 reader here: say so for an HDF5 file (its signature), read text otherwise
        with open(path, "rb") as fh:
            if fh.read(8) == b"\x89HDF\r\n\x1a\n":
                raise ValueError("an HDF5 file: reading it needs h5py (Debian's python3-h5py)") from None
        h5py = None
    if h5py is not None and h5py.is_hdf5(path):
        import shockgas  # the project's one reader of --init files
        x, v, m, ring_length = shockgas.read_initial_condition(path)
        if L is not None and float(L) != ring_length:
            raise ValueError("--L %r, but the file's ring_length is %r" % (float(L), ring_length))
        return x, v, np.ones(len(x)) if m is None else m, ring_length
    Lh = None
    with open(path) as fh:
        for line in fh:
            s = line.strip()
            if s.startswith("#") and "L" in s and "=" in s:
                key, _, val = s.lstrip("#").partition("=")
                if key.strip() == "L":
                    Lh = float(val.split()[0])
    with warnings.catch_warnings():  # no data is said below, in the one error line, not as a warning above it
        warnings.filterwarnings("ignore", message="loadtxt: input contained no data", category=UserWarning)
        data = np.loadtxt(path, comments="#", ndmin=2)
    if data.size == 0:
        raise ValueError("no particles: no line 'x v [m]', only blank lines or '#' comments")
    if data.shape[1] < 2:
        raise ValueError("one column: each line is 'x v [m]'")
    x, v = data[:, 0].copy(), data[:, 1].copy()
    m = data[:, 2].copy() if data.shape[1] > 2 else np.ones(len(x))
    order = np.argsort(x, kind="stable")
    x, v, m = x[order], v[order], m[order]
    if L is None:
        L = Lh if Lh is not None else len(x) * float(np.mean(np.diff(x))) if len(x) > 1 else 1.0
    if not (np.isfinite(L) and L > 0):
        raise ValueError("ring length L = %r: it must be finite and > 0" % L)
    return x, v, m, float(L)


# ----------------------------------------------------------------------------------------------
# vectorised weighted PAV on blocks
# ----------------------------------------------------------------------------------------------
def pav_blocks(W, MX, P, first, t, max_sweeps=100000):
    """Pool blocks until the means y = (MX + t P)/W are non-decreasing.

    W: block masses; MX: sum of m_i x_i (initial); P: block momenta; first: index of the block's
    first particle.  Returns pooled (W, MX, P, first) and the number of sweeps."""
    sweeps = 0
    while sweeps < max_sweeps:
        y = (MX + t * P) / W
        viol = y[:-1] > y[1:]
        if not viol.any():
            break
        starts = np.flatnonzero(np.concatenate(([True], ~viol)))
        W = np.add.reduceat(W, starts)
        MX = np.add.reduceat(MX, starts)
        P = np.add.reduceat(P, starts)
        first = first[starts]
        sweeps += 1
    return W, MX, P, first, sweeps


def pav_stack_reference(y, w):
    """Textbook sequential stack PAV (pure Python, for tests).  Returns block sums and weights."""
    S, Wl = [], []
    for yi, wi in zip(y, w):
        s, ww = yi * wi, wi
        while S and S[-1] / Wl[-1] > s / ww:
            s += S.pop()
            ww += Wl.pop()
        S.append(s)
        Wl.append(ww)
    return np.array(S), np.array(Wl)


def sticky_line(x, v, m, t):
    """Open chain (no boundaries): clusters at time t as dict of arrays."""
    x, v, m = (np.asarray(a, dtype=float) for a in (x, v, m))
    W, MX, P, first, _ = pav_blocks(m.copy(), m * x, m * v, np.arange(len(x)), t)
    return dict(mass=W, momentum=P, velocity=P / W, position=(MX + t * P) / W, first=first)


class TooFewCopies(ValueError):
    """A time past what `copies` periodic images can represent exactly (2 t max|v| >= copies L)."""

    def __init__(self, t, copies, L, vmax):
        self.t, self.copies, self.L, self.vmax = t, copies, L, vmax
        self.needed = int(np.floor(2.0 * t * vmax / L)) + 1
        super().__init__("t = %g too large for %d copies: need 2 t max|v| = %.6g < copies L = %.6g (--copies %d or more)"
                         % (t, copies, 2.0 * t * vmax, copies * L, self.needed))


def sticky_ring(x, v, m, L, times, copies=1, cm_frame=True):
    """Ring of length L.  Returns a list (one per time, times sorted increasingly) of dicts with
    arrays mass, momentum, velocity, position (in [0, L)), first (original particle index)."""
    x, v, m = (np.asarray(a, dtype=float) for a in (x, v, m))
    N = len(x)
    times = np.asarray(times, dtype=float)
    if np.any(np.diff(times) < 0):
        raise ValueError("times must be increasing")
    if cm_frame:
        v = v - np.sum(m * v) / np.sum(m)
    vmax = np.max(np.abs(v))
    if 2.0 * times[-1] * vmax >= copies * L:
        raise TooFewCopies(times[-1], copies, L, vmax)
    shifts = np.arange(-copies, copies + 1)
    X = (x[None, :] + L * shifts[:, None]).ravel()
    V = np.tile(v, len(shifts))
    Mm = np.tile(m, len(shifts))
    W, MX, P, first = Mm.copy(), Mm * X, Mm * V, np.arange(len(X))
    lo, hi = copies * N, (copies + 1) * N
    out = []
    for t in times:
        W, MX, P, first, sweeps = pav_blocks(W, MX, P, first, t)
        sel = (first >= lo) & (first < hi)
        pos = ((MX[sel] + t * P[sel]) / W[sel]) % L
        out.append(dict(t=t, mass=W[sel].copy(), momentum=P[sel].copy(), velocity=P[sel] / W[sel],
                        position=pos, first=first[sel] - lo, sweeps=sweeps))
    return out


def sticky_event_driven_line(x, v, m, t_end):
    """Reference event-driven sticky dynamics on an open line (O(N^2), for small tests only)."""
    pos = list(map(float, x))
    vel = list(map(float, v))
    mas = list(map(float, m))
    firsts = list(range(len(pos)))
    t = 0.0
    while True:
        best, k_best = np.inf, -1
        for k in range(len(pos) - 1):
            dv = vel[k] - vel[k + 1]
            if dv > 0:
                dt = (pos[k + 1] - pos[k]) / dv
                if dt < best:
                    best, k_best = dt, k
        if k_best < 0 or t + best > t_end:
            pos = [p_ + (t_end - t) * u for p_, u in zip(pos, vel)]
            break
        pos = [p_ + best * u for p_, u in zip(pos, vel)]
        t += best
        k = k_best
        M = mas[k] + mas[k + 1]
        vel[k] = (mas[k] * vel[k] + mas[k + 1] * vel[k + 1]) / M
        pos[k] = (mas[k] * pos[k] + mas[k + 1] * pos[k + 1]) / M
        mas[k] = M
        del pos[k + 1], vel[k + 1], mas[k + 1], firsts[k + 1]
    return dict(mass=np.array(mas), velocity=np.array(vel), position=np.array(pos), first=np.array(firsts))


# ----------------------------------------------------------------------------------------------
# observables
# ----------------------------------------------------------------------------------------------
def observables(cl, N=None):
    """T = sum M V^2 / Mtot - (sum M V / Mtot)^2 (per unit mass = per particle for unit masses),
    n = clusters per particle, mass-weighted kurtosis of the velocity."""
    M, Pm = cl["mass"], cl["momentum"]
    Mtot = M.sum()
    N = Mtot if N is None else N
    vbar = Pm.sum() / Mtot
    V = Pm / M - vbar
    T = np.sum(M * V * V) / Mtot
    m4 = np.sum(M * V ** 4) / Mtot
    return dict(T=T, n=len(M) / N, kurtosis=m4 / T ** 2, Mtot=Mtot)


Z_EDGES = np.linspace(-3.5, 3.5, 71)        # bins of z = V t^(1/3)
# A histogram bin enters --hist-dir's chi2 when it holds this many clusters or more over all
# realizations. Its error bar is then its counting error, estimated from the clusters it holds:
# with fewer, chance lows get small error bars and chi2/bins drifts up (measured for Phi at N = 2000
# and 20000 with two realizations: 1.1 to 1.5 per bin from 5 clusters on, 0.8 to 1.1 from 10).
MIN_BIN_CLUSTERS = 10
# The finite-time fit ratio(t) = r_inf + a t^(-1/3) has two parameters: it needs three times or more
# to leave a degree of freedom for its chi2 (with two it passes through both points, chi2 0/0).
MIN_FIT_TIMES = 3
# Its error bars are the standard errors from the spread of the realizations (R - 1 degrees of
# freedom): below this many the fit's chi2/dof is too heavy-tailed to mean anything (module
# docstring: median 2.8 and 1% above 100 with 2; median 1.15 with 5), and the fit is n/a.
MIN_FIT_REALIZATIONS = 5
M_EDGES = np.linspace(0.0, 6.0, 61)         # bins of m = M / M*,  M* = (D t^2)^(1/3)


HISTOGRAM_PARTS = ("density", "sumw2", "clusters")


def histograms(cl, t, D=1.0 / 3.0):
    """One realization's histograms at time t, a dict over
        "z":        mass-weighted histogram density of z = (V - vbar) t^(1/3) (normalised to 1),
        "m_number": clusters per unit scaled length (L/M*) per unit m = M/M* (compare with F(m) of
                    exact_ballistic, NOT renormalised to the simulated cluster count),
        "m_mass":   mass-weighted density of m,
    each a tuple (density, sumw2, clusters) of arrays over the bins (HISTOGRAM_PARTS): the density;
    the sum of the squared weights of the clusters in each bin, a cluster's weight being what it adds
    to the density (M/Mtot/width, or (M*/Mtot)/width for m_number), i.e. the bin's counting variance
    in the density's units squared; and the number of clusters in each bin."""
    M, Pm = cl["mass"], cl["momentum"]
    Mtot = M.sum()
    Ms = (D * t * t) ** (1.0 / 3.0)
    z = (Pm / M - Pm.sum() / Mtot) * t ** (1.0 / 3.0)
    ms = M / Ms
    edges = mass_edges(t, D)
    out = {}
    for key, x, bins, weight in (("z", z, Z_EDGES, M / Mtot), ("m_number", ms, edges, np.full(len(M), Ms / Mtot)),
                                 ("m_mass", ms, edges, M / Mtot)):
        width = np.diff(bins)
        out[key] = (np.histogram(x, bins, weights=weight)[0] / width,
                    np.histogram(x, bins, weights=weight * weight)[0] / width ** 2,
                    np.histogram(x, bins)[0])
    return out


def mass_edges(t, D=1.0 / 3.0):
    """M_EDGES moved to half-integer masses (cluster masses are integers): no aliasing."""
    Ms = (D * t * t) ** (1.0 / 3.0)
    e = np.unique(np.round(M_EDGES * Ms)) + 0.5
    return np.concatenate(([0.0], e[e > 0.5])) / Ms


def run_ensemble(N, realizations, seed, times, copies=1, verbose=True, with_hist=False):
    """Independent realizations (seeds seed, seed+1, ...); returns per-time arrays of T and n
    (and, with_hist, per-realization histograms, see histograms(): out["hist"][key][k] is a dict
    of arrays (realizations, bins at times[k]), "density", "sumw2" and "clusters"))."""
    times = np.asarray(sorted(times), dtype=float)
    T = np.zeros((realizations, len(times)))
    n = np.zeros_like(T)
    kurt = np.zeros_like(T)
    H = {"z": [], "m_number": [], "m_mass": []}
    t0 = time.time()
    for r in range(realizations):
        x, v, m, L = generate_initial(N, seed + r)
        res = sticky_ring(x, v, m, L, times, copies=copies)
        per_time = {key: [] for key in H}
        for k, cl in enumerate(res):
            ob = observables(cl, N)
            assert abs(ob["Mtot"] - N) < 1e-6 * N, "lost mass on the ring"
            T[r, k], n[r, k], kurt[r, k] = ob["T"], ob["n"], ob["kurtosis"]
            if with_hist:
                for key, parts in histograms(cl, times[k]).items():
                    per_time[key].append(parts)
        if with_hist:
            for key in H:
                H[key].append(per_time[key])
        if verbose:
            print("# realization %d done (%.1f s)" % (r, time.time() - t0), file=sys.stderr)
    out = dict(times=times, T=T, n=n, kurtosis=kurt, seconds=time.time() - t0, N=N,
               realizations=realizations, seed=seed, copies=copies)
    if with_hist:
        # Per time arrays (R, nbins): the mass bins (mass_edges) depend on t, and at small t (below
        # ~55 for M_EDGES) rounding to half-integer masses merges some, so times differ in bin count.
        out["hist"] = {key: [{part: np.array([per_realization[k][i] for per_realization in per_key])
                              for i, part in enumerate(HISTOGRAM_PARTS)}
                             for k in range(len(times))] for key, per_key in H.items()}
    return out


def _bin_average(fun, edges, nper=8):
    x, w = np.polynomial.legendre.leggauss(nper)
    lo, hi = edges[:-1, None], edges[1:, None]
    nodes = 0.5 * (hi - lo) * x[None, :] + 0.5 * (hi + lo)
    vals = fun(nodes.ravel()).reshape(nodes.shape)
    return (vals * 0.5 * w[None, :]).sum(axis=1)


def histogram_chi2(hist, theory):
    """The realizations' mean histogram against `theory` (bin averages), bin by bin.

    hist: a dict of arrays (realizations, bins), "density", "sumw2" and "clusters" (histograms(),
    run_ensemble()'s out["hist"][key][k]). The error of the mean in a bin is its counting error,
    sqrt(sum of sumw2 over the realizations) / R: each cluster one count of its weight, whatever the
    number of realizations (an error from their scatter has R - 1 degrees of freedom; with 2 its
    chi2 has no finite mean). Returns (mean, error, z, use): z = (mean - theory) / error in the bins
    used, 0 elsewhere; use: the bins holding MIN_BIN_CLUSTERS clusters or more over all realizations."""
    density, sumw2 = np.asarray(hist["density"], dtype=float), np.asarray(hist["sumw2"], dtype=float)
    clusters = np.asarray(hist["clusters"])
    R = density.shape[0]
    mean = density.mean(axis=0)
    error = np.sqrt(sumw2.sum(axis=0)) / R
    use = clusters.sum(axis=0) >= MIN_BIN_CLUSTERS
    z = np.zeros_like(mean)
    z[use] = (mean[use] - np.asarray(theory, dtype=float)[use]) / error[use]
    return mean, error, z, use


def write_histogram_comparison(ens, out_dir):
    """Write z and m histograms (mean +- counting error over the realizations) next to the exact
    bin-averaged theory; return chi^2 per time (histogram_chi2)."""
    import exact_ballistic as eb
    os.makedirs(out_dir, exist_ok=True)
    R = ens["realizations"]
    th_z = _bin_average(eb.phi, Z_EDGES)
    summary = []
    for k, t in enumerate(ens["times"]):
        rec = dict(t=float(t))
        me = mass_edges(t)
        th_mn = _bin_average(lambda mm: eb.mass_density_from_grid(mm), me)
        th_mm = _bin_average(lambda mm: mm * eb.mass_density_from_grid(mm), me)
        for key, edges, th, name in (("z", Z_EDGES, th_z, "phi"), ("m_number", me, th_mn, "mass_number"),
                                     ("m_mass", me, th_mm, "mass_massweighted")):
            mean, err, z, use = histogram_chi2(ens["hist"][key][k], th)
            rec[name] = dict(chi2=float(np.sum(z ** 2)), nbins=int(use.sum()))
            if key == "m_number":     # first bin (m < 0.1) carries the discreteness deficit
                rec[name]["chi2_without_first_bin"] = float(np.sum(z[1:] ** 2))
                rec[name]["nbins_without_first_bin"] = int(use[1:].sum())
                rec[name]["first_bin_sim_over_theory"] = float(mean[0] / th[0])
            centers = 0.5 * (edges[1:] + edges[:-1])
            with atomic_output(os.path.join(out_dir, "%s_t%g.dat" % (name, t)), "w") as fh:
                fh.write("# PAV sticky gas N=%d, %d realizations, t=%g; theory = exact_ballistic bin average\n"
                         % (ens["N"], R, t))
                fh.write("# sim: mean over realizations; sim_err: its counting error (each cluster one count of "
                         "its weight)\n")
                fh.write("# %s lo hi sim sim_err theory\n" % ("z" if key == "z" else "m"))
                for c, lo, hi, a, b, c2 in zip(centers, edges[:-1], edges[1:], mean, err, th):
                    fh.write("%.6g %.6g %.6g %.8e %.3e %.8e\n" % (c, lo, hi, a, b, c2))
        summary.append(rec)
    return summary


def per_realization_ratios(ens, kappa, nu):
    """Each realization's T t^(2/3)/kappa, n t^(2/3)/nu and kurtosis of Phi at the ensemble's times: a
    dict of arrays (realizations, times), "T_ratio", "n_ratio" and "kurtosis"."""
    s = ens["times"] ** (2.0 / 3.0)
    return dict(T_ratio=ens["T"] * s / kappa, n_ratio=ens["n"] * s / nu, kurtosis=ens["kurtosis"])


def compare_table(times, ratios):
    """Rows, one per time: t, and for each of `ratios` (per_realization_ratios) the mean over the
    realizations and its standard error from their spread (`<key>_err`, NaN with one realization)."""
    rows = []
    for k, t in enumerate(times):
        row = dict(t=t)
        for key, values in ratios.items():
            at_t = values[:, k]
            row[key] = at_t.mean()
            row[key + "_err"] = at_t.std(ddof=1) / np.sqrt(len(at_t)) if len(at_t) > 1 else np.nan
        rows.append(row)
    return rows


def fit_finite_time(rows, key, samples, tmin=0.0):
    """Weighted least squares  ratio(t) = r_inf + a t^(-1/3)  (leading discreteness correction) to the
    rows' means, weighted by their errors (compare_table). samples: each realization's value at the
    rows' times (realizations x times, per_realization_ratios()[key]).

    r_inf_err and a_err are the delete-one jackknife over the realizations, as shockgas-analyze's
    errors are (analysis/README.md): the fit redone on the means without each realization, its
    weights kept, sigma^2 = (R - 1)/R sum_i (theta_(i) - mean theta)^2. The values of one realization
    at different times are correlated (its clusters only merge), which the fit's own widths,
    r_inf_fit_err and a_fit_err, ignore by taking the times as independent: they come out about half
    of the spread of r_inf over ensembles (module docstring). chi2 and dof are those of the same
    fit, a diagnostic of the shape rather than a goodness of fit. Where there is no fit to make, the
    numbers are None and `note` says why: fewer than MIN_FIT_REALIZATIONS realizations, a time with
    an error of 0 (every realization holds the same value) or none (NaN)."""
    samples = np.asarray(samples, dtype=float)
    used = np.array([r["t"] >= tmin for r in rows])
    t = np.array([r["t"] for r in rows])[used]
    y = np.array([r[key] for r in rows], dtype=float)[used]
    e = np.array([r[key + "_err"] for r in rows], dtype=float)[used]
    samples = samples[:, used]
    realizations = samples.shape[0]
    note = None
    if realizations < MIN_FIT_REALIZATIONS:
        note = ("its error bars come from the spread of the realizations: the fit needs %d or more, not %d"
                % (MIN_FIT_REALIZATIONS, realizations))
    elif not np.all(np.isfinite(e) & (e > 0) & np.isfinite(y)):
        bad = [float(u) for u, v, w in zip(t, y, e) if not (np.isfinite(w) and w > 0 and np.isfinite(v))]
        note = ("no error bar at t = %s: every realization holds the same value there (or none), no spread to "
                "weight the fit by" % ", ".join("%g" % u for u in bad))
    if note is not None:
        return dict(r_inf=None, r_inf_err=None, a=None, a_err=None, r_inf_fit_err=None, a_fit_err=None, chi2=None,
                    dof=len(t) - 2, note=note)
    design = np.vstack([np.ones_like(t), t ** (-1.0 / 3.0)]).T / e[:, None]

    def fit(means):
        return np.linalg.lstsq(design, means / e, rcond=None)[0]

    coef = fit(y)
    replicas = np.array([fit(np.delete(samples, i, axis=0).mean(axis=0)) for i in range(realizations)])
    jackknife = np.sqrt((realizations - 1) / realizations * np.sum((replicas - replicas.mean(axis=0)) ** 2, axis=0))
    cov = np.linalg.inv(design.T @ design)
    chi2 = float(np.sum((design @ coef - y / e) ** 2))
    return dict(r_inf=coef[0], r_inf_err=jackknife[0], a=coef[1], a_err=jackknife[1], r_inf_fit_err=np.sqrt(cov[0, 0]),
                a_fit_err=np.sqrt(cov[1, 1]), chi2=chi2, dof=len(t) - 2)


def main(argv=None):
    ap = ArgumentParser(description="exact sticky-gas state by isotonic regression (PAV)")
    ap.add_argument("--N", type=int, default=1000000)
    ap.add_argument("--realizations", type=int, default=5)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--times", type=float, nargs="+",
                    default=[100, 215.443469, 464.158883, 1000, 2154.43469, 4641.58883, 10000])
    ap.add_argument("--copies", type=int, default=1, help="periodic copies on each side")
    ap.add_argument("--init", help="one start instead (one realization): a text file of lines 'x v [m]', or "
                                   "shockgas-sim's HDF5 --init file; every x in [0, L)")
    ap.add_argument("--L", type=float, help="ring length for a text --init (default: its '# L = ' line, else N "
                                            "times the mean spacing; an HDF5 file's is its ring_length)")
    ap.add_argument("--clusters-out", help="with --init: write clusters 't mass position velocity' here")
    ap.add_argument("--compare", action="store_true", help="compare with exact_ballistic kappa, nu")
    ap.add_argument("--json", help="write the comparison table as JSON here")
    ap.add_argument("--hist-dir", help="with --compare: write Phi and mass histograms vs theory here")
    args = ap.parse_args(argv)
    # A user's mistake, found in the arguments, the --init file or the times the copies reach, is the
    # parser's one line (shockgas.cli).
    try:
        check_arguments(args)
        check_outputs(args)
        return solve(args)
    except (InputError, TooFewCopies) as error:
        ap.error(str(error))


def solve(args):
    """What main() does with checked arguments: --init's clusters, or the ensemble and its comparison."""
    if args.init:
        try:
            x, v, m, L = read_initial(args.init, args.L)
        except (OSError, ValueError, IndexError) as error:
            raise InputError("%s: not a readable initial condition 'x v [m]' (%s)" % (args.init, error)) from None
        if len(x) < 2 or not (np.all(np.isfinite(x)) and np.all(np.isfinite(v)) and np.all(np.isfinite(m) & (m > 0))):
            raise InputError("%s: needs N >= 2 particles with finite x and v and finite masses > 0" % args.init)
        # The ring is [0, L): a particle outside it would be unrolled into the wrong periodic copy, and
        # drop out of the clusters (as reference_gas.py and shockgas-sim, refused rather than wrapped).
        outside = np.flatnonzero((x < 0) | (x >= L))
        if outside.size:
            raise InputError("%s: x = %r%s lies outside the ring [0, L = %r)%s" % (
                args.init, float(x[outside[0]]), " (and %d more)" % (outside.size - 1) if outside.size > 1 else "", L,
                "" if args.L is not None else " (L from the file's '# L =' line or N times the mean spacing; "
                                             "give --L)"))
        res = sticky_ring(x, v, m, L, sorted(args.times), copies=args.copies)
        if not args.clusters_out:
            write_clusters(sys.stdout, res)
            return 0
        # Closed here, so that a failure to write (a full disk) is told, not lost at exit.
        with writing(args.clusters_out, "--clusters-out"):
            with atomic_output(args.clusters_out, "w") as fh:
                write_clusters(fh, res)
        return 0

    ens = run_ensemble(args.N, args.realizations, args.seed, args.times, args.copies,
                       with_hist=bool(args.hist_dir))
    print("# N = %d, realizations = %d, seeds %d.., copies = %d, wall time %.1f s"
          % (args.N, args.realizations, args.seed, args.copies, ens["seconds"]))
    if not args.compare:
        print("# t  <T>  <n>")
        for k, t in enumerate(ens["times"]):
            print("%g %.8e %.8e" % (t, ens["T"][:, k].mean(), ens["n"][:, k].mean()))
        return 0
    import exact_ballistic as eb
    const = eb.compute_constants(check_resolution=False)
    ratios = per_realization_ratios(ens, const["kappa"], const["nu"])
    rows = compare_table(ens["times"], ratios)
    print("# kappa = %.8f, nu = %.8f, kurtosis(Phi) = %.6f" % (const["kappa"], const["nu"], const["kurtosis"]))
    print("# %10s %22s %22s %18s" % ("t", "T t^(2/3)/kappa", "n t^(2/3)/nu", "kurtosis"))
    for r in rows:
        print("%12.1f %12.5f +- %.5f %12.5f +- %.5f %9.4f +- %.4f"
              % (r["t"], r["T_ratio"], r["T_ratio_err"], r["n_ratio"], r["n_ratio_err"], r["kurtosis"], r["kurtosis_err"]))
    fits = {key: fit_finite_time(rows, key, ratios[key]) for key in ("T_ratio", "n_ratio")}
    for key, f in fits.items():
        if f["r_inf"] is None:
            print("# fit %s = r_inf + a t^(-1/3): n/a (%s)" % (key, f["note"]))
            continue
        print("# fit %s = r_inf + a t^(-1/3): r_inf = %.5f +- %.5f, a = %.4f +- %.4f (jackknife over realizations), "
              "chi2/dof = %.2f/%d; the fit's own widths, the times taken as independent: +- %.5f, +- %.4f"
              % (key, f["r_inf"], f["r_inf_err"], f["a"], f["a_err"], f["chi2"], f["dof"], f["r_inf_fit_err"],
                 f["a_fit_err"]))
    hist = None
    if args.hist_dir:
        with writing(args.hist_dir, "--hist-dir"):
            hist = write_histogram_comparison(ens, args.hist_dir)
        def chi2(value, bins):
            return "%.1f/%d" % (value, bins) if bins > 0 else "n/a/0"

        for rec in hist:
            phi, mn, mm = rec["phi"], rec["mass_number"], rec["mass_massweighted"]
            print("# t = %g: chi2/bins  Phi %s   F(m) %s (without m<0.1 bin: %s, that bin sim/theory %.3f)"
                  "   m F(m) %s"
                  % (rec["t"], chi2(phi["chi2"], phi["nbins"]), chi2(mn["chi2"], mn["nbins"]),
                     chi2(mn["chi2_without_first_bin"], mn["nbins_without_first_bin"]),
                     mn["first_bin_sim_over_theory"], chi2(mm["chi2"], mm["nbins"])))
    if args.json:
        with writing(args.json, "--json"):
            with atomic_output(args.json, "w") as fh:
                json.dump(dict(N=args.N, realizations=args.realizations, seed=args.seed, copies=args.copies,
                               seconds=ens["seconds"], kappa=const["kappa"], nu=const["nu"],
                               kurtosis_exact=const["kurtosis"], rows=rows, fits=fits, histograms=hist),
                          fh, indent=2, default=float)
    return 0


def write_clusters(fh, res):
    fh.write("# t mass position velocity first_particle\n")
    for cl in res:
        for a, b, c, d in zip(cl["mass"], cl["position"], cl["velocity"], cl["first"]):
            fh.write("%.10g %.10g %.12g %.12g %d\n" % (cl["t"], a, b, c, d))


class InputError(Exception):
    """A user's mistake (exit 2, one line)."""


@contextlib.contextmanager
def writing(path, option):
    """with writing(path, option): an OSError while writing `path` (the option's value, or a file in
    it for a directory) is the InputError "cannot write <option> '<file>': <cause>"."""
    try:
        yield
    except OSError as error:
        raise InputError(cannot_write(error.filename or path, error, option)) from None


def check_arguments(args):
    """Refuses, as InputError, what would crash or print a meaningless fit."""
    times = np.asarray(args.times, dtype=float)
    if not np.all(np.isfinite(times) & (times > 0)):
        raise InputError("--times: every time must be finite and > 0")
    if args.copies < 1:
        raise InputError("--copies %d: at least 1" % args.copies)
    if args.init:
        if args.compare or args.hist_dir or args.json:
            raise InputError("--compare, --hist-dir and --json are for ensembles, not --init")
        if args.L is not None and not (np.isfinite(args.L) and args.L > 0):
            raise InputError("--L %r: a ring length > 0" % args.L)
        return
    if args.clusters_out:
        raise InputError("--clusters-out goes with --init")
    if args.N < 2:
        raise InputError("--N %d: at least 2 particles" % args.N)
    if args.realizations < 1:
        raise InputError("--realizations %d: at least 1" % args.realizations)
    if (args.hist_dir or args.json) and not args.compare:
        raise InputError("--hist-dir and --json write the comparison: add --compare")
    if args.compare:
        if len(set(times.tolist())) < MIN_FIT_TIMES:
            raise InputError("--compare fits ratio(t) = r_inf + a t^(-1/3) (2 parameters) over the times: it needs "
                             "%d or more different --times, not %d" % (MIN_FIT_TIMES, len(set(times.tolist()))))
        if args.realizations < 2:
            raise InputError("--compare takes its error bars from the spread over realizations: "
                             "--realizations 2 or more")


def check_outputs(args):
    """Refuses, as InputError, an output that cannot be written, now rather than after the work
    (shockgas.cli: a missing directory, a file in the way, no permission, a read-only file system)."""
    for option, path, problem in (("--clusters-out", args.clusters_out, output_file_problem),
                                  ("--json", args.json, output_file_problem),
                                  ("--hist-dir", args.hist_dir, output_directory_problem)):
        why = problem(path) if path is not None else None
        if why is not None:
            raise InputError(cannot_write(path, why, option))


if __name__ == "__main__":
    sys.exit(main())
