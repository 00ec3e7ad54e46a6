#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Exact asymptotic theory of 1D ballistic aggregation (sticky gas, r = 0) in shockgas units.

Run with Debian's interpreter (needs numpy + scipy):
    /usr/bin/python3 python/exact_ballistic.py --out-dir DIR

The joint density (EB3) was derived here from the Brownian picture and afterwards found to be
identical, prefactors included, to Frachebourg-Martin-Piasecki's result (the small- and large-mass
asymptotes FMP (108)-(109) map exactly onto (EB11)-(EB12) under fmp_mapping()).  It is checked
numerically by exact sum rules, by an independent contour formula for the mass distribution
(FMP (105)-(106)), and against the exact sticky-gas simulation sticky_pav.py.  No code was taken
from anywhere.  Equation labels (EB1)...(EB12) refer to this docstring; "FMP (n)" is equation (n)
of Frachebourg, Martin & Piasecki, Physica A 279, 69 (2000), arXiv:cond-mat/9911346.

Units of shockgas
-----------------
Point particles of unit mass, initially at x_i = i (spacing 1, mass density rho = 1), i.i.d.
velocities uniform on [-1, 1]  ->  <v^2> = 1/3, on a ring of length L = N.

(EB1) Variational principle (E, Rykov & Sinai, CMP 177, 349 (1996)).  Let mu be the Lagrangian
      mass coordinate and P(mu) the cumulative initial momentum.  At time t the clusters are the
      faces of the convex minorant of
          Y(mu) = mu^2 / (2 rho) + t P(mu)          (cumulative sum of y_i = x_i + t v_i).
      A face [mu1, mu2] is a cluster of mass mu2 - mu1 and momentum P(mu2) - P(mu1).

(EB2) Central-limit scaling.  P(mu) has independent increments with Var[P(mu)] = D mu / rho,
      where D = n_p m_p^2 <v^2> (n_p particles per length, m_p particle mass) is the momentum
      variance per unit LENGTH; P(mu) converges to Brownian motion (Donsker).  Ours: D = 1/3.
      Only rho and D (and t) enter, so by dimensional analysis (set mu = M* s):
          M*  = (D rho t^2)^(1/3)             mass unit         (= (t^2/3)^(1/3) for us)
          ell = M*/rho = (D t^2/rho^2)^(1/3)  length unit
          P*  = sqrt(D ell)                   momentum unit
          V*  = P*/M* = ell/t                 velocity unit     (= D^(1/3) t^(-1/3) for rho = 1)
      and Y(M* s) / (t P*) = s^2/2 + W(s)  with W a standard two-sided Brownian motion.
      So in scaled variables (m = M/M*, p = P/P*, w = p/m = V/V*) the problem is the convex
      minorant of F(s) = s^2/2 + W(s)  (curvature coefficient c = 1/2, unit variance).

(EB3) Face (cluster) intensity.  By the Markov property the face [s1, s1+m] with momentum p exists
      iff (i) the path left of s1 stays above the face line, (ii) the bridge inside stays above
      the chord, (iii) the path right of s2 stays above the line.  Relative to the line, the
      outside pieces are D(u) = b u + u^2/2 + W(u) (u >= 0) with drifts
          b_L = m/2 + p/m ,   b_R = m/2 - p/m,
      and the inside piece is a Brownian bridge above the arch u(m-u)/2.  The density of faces
      per unit s, per unit m, per unit p is
          f(m, p) = (1/4) psi(b_L) psi(b_R) * phi_m(p) * (2/m) * exp(-m^3/24) * E_exc(m)
                  = (1/2) psi(b_L) psi(b_R) exp(-p^2/(2m) - m^3/24) S(m)              (EB3)
      where the 1/4 = (1/2)^2 is the vertex factor that turns two one-sided d/d(epsilon)
      survival derivatives into a location density (the same 1/2 as in the arcsine law and in
      Chernoff's density f(t) = g(t)g(-t)/2), phi_m the N(0, m) density, and the bridge factor
      was reduced by Cameron-Martin to Brownian-excursion area A:  E_exc(m) = E[exp(-m^{3/2}A)].
      This is FMP (72) with (95)-(98), i.e. FMP (104), written in our normalisation; see
      `fmp_mapping()` for the exact change of variables (b_FMP = 1 <-> M_FMP = m / 2^(1/3)).
      It is checked by the exact sum rule  int int m f dm dp = 1  (faces tile the line), which
      the implementation satisfies to ~1e-10, and by direct simulation (sticky_pav.py).

(EB4) One-sided factor (Groeneboom, Probab. Th. Rel. Fields 81, 79 (1989); FMP (97)-(98)):
          psi(b) = exp(b^3/6) g(b),  g(b) = (1/2pi) int ds exp(-i s b) 4^(1/3) / Ai(i 2^(1/3) s)
      psi(b) = d/d(eps) P[eps + b u + u^2/2 + W(u) > 0 for all u > 0] at eps = 0.
      Checks: int psi(b) psi(-b) db / 2 = 1 (Chernoff normalisation), psi(b) = 2b + 1/b^2 + ...
      for b -> +inf (constant-drift limit).  For b < 0 the contour closes on the Airy zeros a_k:
          psi(b) = 2^(1/3) exp(-|b|^3/6) sum_k exp(-|a_k| |b| / 2^(1/3)) / Ai'(a_k)    (EB4')
      (FMP (101)).  For b > 0 the Fourier contour is shifted to Im s = -b^2/2 (the saddle point),
      which removes the exp(b^3/6) cancellation; scipy.special.airye supplies scaled Airy values.

(EB5) Excursion-area Laplace transform (Louchard, J. Appl. Prob. 21, 479 (1984); Janson,
      Probab. Surveys 4, 80 (2007)):  E[exp(-lam A)] = sqrt(2 pi) lam sum_j exp(-|a_j| lam^(2/3)/2^(1/3)).
      With lam = m^(3/2):   S(m) = sum_j exp(-|a_j| m / 2^(1/3)) = E_exc(m) / (sqrt(2 pi) m^(3/2)),
      which is FMP (96) I(M).  Check: 1 - E_exc(m) ~ sqrt(pi/8) m^(3/2) = E[A] m^(3/2).
      The zero sum is done exactly for j <= 1000, the rest by Euler-Maclaurin with the asymptotic
      zeros (valid down to m ~ 1e-8).

Derived quantities (scaled, then in our units with D = 1/3, rho = 1)
(EB6)  N_s = int int f dm dp  (clusters per unit s);   n(t) = N_s / ell = nu t^(-2/3),
       nu = N_s D^(-1/3).
(EB7)  K = int int (p^2/m) f dm dp;  T(t) = sum M V^2 / N = K D / ell = kappa t^(-2/3),
       kappa = K D^(2/3).   (Mass-weighted temperature per particle; the ring is in the CM frame.)
(EB8)  Mass-weighted velocity density in w = V/V*:  P_w(w) = int m^2 f(m, w m) dm  (norm. 1 by EB3
       sum rule);  Phi(z) = D^(-1/3) P_w(z D^(-1/3)),  z = V t^(1/3).   Var Phi = kappa exactly.
(EB9)  Tail (derived here from EB3 + EB4' by Laplace's method at m ~ 6/w^2; cf. the bound FMP (111)):
       P_w(w) ~ (2^(11/6)/Ai'(a_1)) w^-2 exp(-w^3/6 - |a_1| w / 2^(1/3)), relative corrections
       O(1/w^2) (measured: Phi/asymptote - 1 = 0.09, 0.05, 0.03 at z = 4, 6, 8), hence
       Phi(z) ~ (2^(11/6) D^(1/3)/Ai'(a_1)) z^-2 exp(-z^3/(6D) - |a_1| z/(2D)^(1/3)),
       i.e. the cubic tail constant is c = 1/(6D) = 1/2 for our units.
(EB10) Mass distribution (clusters per unit s per unit m): F(m) = int f dp = m S(m) H(m/2^(1/3)),
       H(mu) = (1/2 pi i) int_{-i inf}^{i inf} dw exp(-mu w)/Ai(w)^2   (FMP (105)-(106)).
(EB11) Small m:  F(m) = (2 pi m)^(-1/2) (1 + O(m))  (measured: F/asym - 1 = 0.98 m)   (FMP (108)).
(EB12) Large m:  F(m) ~ sqrt(pi/2) m^(5/2) exp(-m^3/24 - |a_1| m / 2^(1/3))   (FMP (109)),
       (measured relative correction ~ 3.7-3.9/m^3 for m = 5..11).
       In FMP's variable with b = 1, mu = m/2^(1/3), the cubic factor is exp(-mu^3/12);
       in raw units M t^(-2/3) (ours) it is exp(-(M t^(-2/3))^3 / 8).
(EB13) The uniform start at finite t (derived here; first order in the law's departure from the
       Gaussian).  EB9's saddle in lattice units: the tagged cluster, mass M = 6/w^2 M*, moves at
       V = z t^(-1/3), and the L = V t particles ahead carry the ramp u_i = V (1 - i/L).  A smooth
       profile of i.i.d. velocities costs sum_i I(u_i) (Mogulskii), with I the Cramer rate of one
       velocity: 3u^2/2 for the Gaussian of variance 1/3, and for the uniform law on [-1, 1]
           I(u) = lam u - ln(sinh(lam)/lam),  coth(lam) - 1/lam = u,   = 3u^2/2 + 9u^4/20 + O(u^6).
       Evaluated on the Gaussian saddle (first order: the saddle's own shift is second order),
           ln Phi_uniform(z, t) - ln Phi(z) = -sum_{i=1}^{L} [I(u_i) - 3u_i^2/2] - M [I(V) - 3V^2/2]
                                            ~ -(9/100) z^5 t^(-2/3) (ramp, leading order in V),
       and Phi_uniform = 0 for V >= 1 (z >= t^(1/3)).  Because the saddle can relax, the true shift
       is no larger than this; it vanishes as t^(-2/3) at fixed z, so the uniform start has the same
       Phi and the same cubic tail as t -> infinity.
"""
import json
import os
import sys

try:
    import numpy as np
    from scipy import interpolate, special
except ImportError as error:  # pragma: no cover - depends on the machine
    # Named after the program that runs: this script, or sticky_pav.py --compare, which imports it.
    print("%s: error: %s is missing: run it with Debian's /usr/bin/python3 (python3-numpy, python3-scipy)"
          % (os.path.basename(sys.argv[0]) or "exact_ballistic.py", error.name or error), file=sys.stderr)
    sys.exit(2)

try:  # one-line refusals, exit status 2 (python/shockgas/cli.py, the project's one place for them)
    from shockgas.cli import ArgumentParser, atomic_output, cannot_write, output_directory_problem
except ImportError:
    # The figure project of an installation runs this script (numpy and scipy) from share/shockgas/python
    # with no PYTHONPATH, where the shockgas module (numpy and h5py) is not on Python's path for every
    # prefix: it then runs all the same, with argparse's usage block above an error line, an
    # --out-dir that cannot be written is found when it is made or written rather than before, and
    # its files are written in place (open), not beside and renamed.
    from argparse import ArgumentParser

    def atomic_output(path, mode="w"):
        return open(path, mode)

    def output_directory_problem(path):
        return None

    def cannot_write(path, cause, option=None):
        return "cannot write %s'%s': %s" % (option + " " if option else "", path,
                                           getattr(cause, "strerror", None) or cause)

C13 = 2.0 ** (1.0 / 3.0)
D_SHOCKGAS = 1.0 / 3.0     # momentum variance per unit length: rho * <v^2> with v ~ U[-1,1], rho = 1

_NZ = 1000
_AZ, _, _, _AIP = special.ai_zeros(_NZ)     # a_k < 0 and Ai'(a_k)
ALPHA = -_AZ                                # |a_k|
ALPHA1 = float(ALPHA[0])
AIP1 = float(_AIP[0])


def _gauss_legendre_panels(a, b, npan, nper):
    x, w = np.polynomial.legendre.leggauss(nper)
    edges = np.linspace(a, b, npan + 1)
    lo, hi = edges[:-1, None], edges[1:, None]
    nodes = 0.5 * (hi - lo) * x[None, :] + 0.5 * (hi + lo)
    weights = 0.5 * (hi - lo) * w[None, :]
    return nodes.ravel(), weights.ravel()


# ----------------------------------------------------------------------------------------------
# (EB4) one-sided factor psi(b)
# ----------------------------------------------------------------------------------------------
_S_NODES, _S_W = _gauss_legendre_panels(0.0, 40.0, 80, 16)


def psi_fourier(b):
    """psi(b) from the Fourier representation (EB4) [Groeneboom 1989; FMP (97)-(98)].

    Contour shifted to Im s = -b^2/2 for b > 0 (saddle point), Im s = 0 for b <= 0.
    Accurate to ~1e-12 relative for -1.5 <= b <= 20 (use psi_series below -1)."""
    b = np.atleast_1d(np.asarray(b, dtype=float))
    eta = np.where(b > 0, 0.5 * b * b, 0.0)
    out = np.empty_like(b)
    for i0 in range(0, len(b), 256):          # chunk to bound memory
        bb, ee = b[i0:i0 + 256, None], eta[i0:i0 + 256, None]
        z = C13 * (ee + 1j * _S_NODES[None, :])
        eai = special.airye(z)[0]            # Ai(z) exp(2/3 z^{3/2})
        expo = bb ** 3 / 6.0 - ee * bb - 1j * _S_NODES[None, :] * bb + (2.0 / 3.0) * z ** 1.5
        integrand = (np.exp(expo) * 4.0 ** (1.0 / 3.0) / eai).real
        out[i0:i0 + 256] = (integrand * _S_W[None, :]).sum(axis=1) / np.pi
    return out


def psi_series(b, nterms=200):
    """psi(b) for b < 0 from the Airy-zero residue series (EB4') [FMP (101)]."""
    b = np.atleast_1d(np.asarray(b, dtype=float))
    if np.any(b >= 0):
        raise ValueError("psi_series needs b < 0")
    ab = np.abs(b)[:, None]
    terms = np.exp(-ALPHA[None, :nterms] * ab / C13) / _AIP[None, :nterms]
    return np.exp(-ab[:, 0] ** 3 / 6.0) * C13 * terms.sum(axis=1)


class _PsiTable:
    """Cubic spline of log psi on [-12, 18] (step 0.01); relative error ~1e-11."""
    BMIN, BMAX, STEP = -12.0, 18.0, 0.01

    def __init__(self):
        self.grid = np.arange(self.BMIN, self.BMAX + 0.5 * self.STEP, self.STEP)
        vals = np.empty_like(self.grid)
        neg = self.grid < -1.0
        vals[neg] = psi_series(self.grid[neg])
        vals[~neg] = psi_fourier(self.grid[~neg])
        self.spline = interpolate.CubicSpline(self.grid, np.log(vals))

    def __call__(self, b):
        b = np.asarray(b, dtype=float)
        out = np.exp(self.spline(np.clip(b, self.BMIN, self.BMAX)))
        out = np.where(b < self.BMIN, 0.0, out)      # psi(-12) ~ 1e-300: negligible
        big = np.maximum(b, 1.0)
        out = np.where(b > self.BMAX, 2.0 * big + 1.0 / big ** 2, out)
        return out


_PSI = None


def psi(b):
    """One-sided survival-derivative factor psi(b) (EB4), vectorised, via a cached spline."""
    global _PSI
    if _PSI is None:
        _PSI = _PsiTable()
    return _PSI(b)


# ----------------------------------------------------------------------------------------------
# (EB5) Airy-zero sum S(m) and excursion-area Laplace transform
# ----------------------------------------------------------------------------------------------
def airy_zero_sum(m):
    """S(m) = sum_j exp(-|a_j| m / 2^(1/3))  (EB5) [FMP (96) with b = 1 after m -> m/2^(1/3)].

    Exact zeros for j <= 1000, Euler-Maclaurin (midpoint) tail with the asymptotic zeros
    |a_j| = t^(2/3) (1 + 5/(48 t^2)), t = 3 pi (4j - 1)/8; dj/d|a| = sqrt|a|/pi + O(|a|^-5/2)
    (dropped term < 1e-5 absolute, i.e. < 1e-9 relative for m < 1)."""
    m = np.atleast_1d(np.asarray(m, dtype=float))
    shape = m.shape
    m, inv = np.unique(m.ravel(), return_inverse=True)     # S depends on m only: evaluate once
    kap = m / C13
    direct = np.empty_like(kap)
    for i0 in range(0, len(kap), 512):                      # chunks bound memory (512 x 1000)
        direct[i0:i0 + 512] = np.exp(-kap[i0:i0 + 512, None] * ALPHA[None, :]).sum(axis=1)
    jh = _NZ + 0.5
    t = 3.0 * np.pi * (4.0 * jh - 1.0) / 8.0
    a_edge = t ** (2.0 / 3.0) * (1.0 + 5.0 / (48.0 * t * t))
    with np.errstate(divide="ignore", invalid="ignore"):
        tail = special.gamma(1.5) * special.gammaincc(1.5, kap * a_edge) / (np.pi * kap ** 1.5)
    tail = np.where(kap > 0, tail, np.inf)
    tail += kap * (np.pi / np.sqrt(a_edge)) * np.exp(-kap * a_edge) / 24.0
    return (direct + tail)[inv].reshape(shape)


def excursion_area_laplace(m):
    """E[exp(-m^{3/2} A)], A = area of the standard Brownian excursion (EB5)."""
    m = np.atleast_1d(np.asarray(m, dtype=float))
    return np.sqrt(2.0 * np.pi) * m ** 1.5 * airy_zero_sum(m)


# ----------------------------------------------------------------------------------------------
# (EB3) joint mass-momentum density
# ----------------------------------------------------------------------------------------------
def joint_density(m, p):
    """f(m, p): clusters per unit s, per unit scaled mass m, per unit scaled momentum p  (EB3).

    Same content as FMP (104); normalised by int int m f = 1."""
    m, p = np.broadcast_arrays(np.asarray(m, dtype=float), np.asarray(p, dtype=float))
    w = p / m
    S = airy_zero_sum(m)
    return 0.5 * psi(0.5 * m + w) * psi(0.5 * m - w) * np.exp(-p * p / (2.0 * m) - m ** 3 / 24.0) * S


def joint_density_mw(m, w):
    """Density of clusters per unit s, per unit m, per unit velocity w = p/m:  m f(m, m w)."""
    m, w = np.broadcast_arrays(np.asarray(m, float), np.asarray(w, float))
    S = airy_zero_sum(m)
    return m * 0.5 * psi(0.5 * m + w) * psi(0.5 * m - w) * np.exp(-0.5 * w * w * m - m ** 3 / 24.0) * S


def scales(t, D=D_SHOCKGAS, rho=1.0):
    """(EB2) mass, length, momentum, velocity units at time t."""
    Mstar = (D * rho * t * t) ** (1.0 / 3.0)
    ell = Mstar / rho
    Pstar = np.sqrt(D * ell)
    Vstar = ell / t
    return dict(Mstar=Mstar, ell=ell, Pstar=Pstar, Vstar=Vstar)


def cluster_density_physical(M, P, t, D=D_SHOCKGAS):
    """Clusters per unit length (= per particle, rho = 1) per unit mass M per unit momentum P."""
    sc = scales(t, D)
    return joint_density(M / sc["Mstar"], P / sc["Pstar"]) / (sc["ell"] * sc["Mstar"] * sc["Pstar"])


# ----------------------------------------------------------------------------------------------
# integrals over (m, w):  m = u^2 removes the m^-1/2 edge
# ----------------------------------------------------------------------------------------------
def _grid(nu_pan=40, nw_pan=80, nper=16, umax=np.sqrt(13.0), wmax=10.0):
    u, uw = _gauss_legendre_panels(0.0, umax, nu_pan, nper)
    w, ww = _gauss_legendre_panels(-wmax, wmax, nw_pan, nper)
    M = (u ** 2)[:, None]
    Wv = w[None, :]
    dens = joint_density_mw(M, Wv)                   # per (s, m, w)
    weight = (2.0 * u * uw)[:, None] * ww[None, :]   # dm dw
    return M, Wv, dens * weight


def scaled_moments(**grid_kw):
    """Moments of the scaled solution: N_s, mass sum rule, K, <w^4>_mass."""
    M, W, dw = _grid(**grid_kw)
    Ns = dw.sum()
    mass = (M * dw).sum()
    K = (M * W ** 2 * dw).sum()
    W4 = (M * W ** 4 * dw).sum()
    return dict(N_s=Ns, mass_sum_rule=mass, K=K, w4_massweighted=W4, kurtosis=W4 / K ** 2)


def velocity_density_w(w, massweighted=True, nu_pan=60, nper=16, umax=np.sqrt(13.0)):
    """(EB8) P_w(w) = int m^2 f(m, w m) dm (mass weighted) or int m f dm / N_s (number weighted)."""
    w = np.atleast_1d(np.asarray(w, dtype=float))
    u, uw = _gauss_legendre_panels(0.0, umax, nu_pan, nper)
    M = (u ** 2)[:, None]
    dens = joint_density_mw(M, w[None, :])
    wt = (2.0 * u * uw)[:, None]
    if massweighted:
        return (M * dens * wt).sum(axis=0)
    return (dens * wt).sum(axis=0)


def phi(z, D=D_SHOCKGAS):
    """Phi(z), z = v t^(1/3): mass-weighted scaling function of P(v,t) = t^(1/3) Phi(v t^(1/3)) (EB8)."""
    s = D ** (1.0 / 3.0)
    return velocity_density_w(np.asarray(z, float) / s) / s


def phi_tail_asymptote(z, D=D_SHOCKGAS):
    """(EB9) leading large-|z| form of Phi."""
    z = np.abs(np.asarray(z, dtype=float))
    with np.errstate(divide="ignore"):
        return (2.0 ** (11.0 / 6.0) * D ** (1.0 / 3.0) / AIP1 * z ** -2.0
                * np.exp(-z ** 3 / (6.0 * D) - ALPHA1 * z / (2.0 * D) ** (1.0 / 3.0)))


def uniform_velocity_rate(u):
    """(EB13) Cramer rate I(u) of one velocity uniform on [-1, 1] (mean u of its tilted law)."""
    u = abs(float(u))
    if u >= 1.0:
        return np.inf
    if u < 1e-4:
        return 1.5 * u * u + 0.45 * u ** 4  # the series: the root below is ill-conditioned near 0
    from scipy.optimize import brentq
    lam = brentq(lambda l: 1.0 / np.tanh(l) - 1.0 / l - u, 1e-6, 1e7, xtol=1e-14, rtol=1e-15)
    # ln(sinh(lam)/lam) written so that it does not overflow for large lam
    return lam * u - (lam + np.log1p(-np.exp(-2.0 * lam)) - np.log(2.0 * lam))


def uniform_start_log_phi_shift(z, t, D=D_SHOCKGAS):
    """(EB13) ln Phi_uniform(z, t) - ln Phi(z) at first order, for z > 0 (-inf where z >= t^(1/3))."""
    V = z * t ** (-1.0 / 3.0)
    if V >= 1.0:
        return -np.inf
    ramp_sites = np.arange(1, int(V * t) + 1)
    u = V * (1.0 - ramp_sites / (V * t))
    ramp = sum(uniform_velocity_rate(x) - 1.5 * x * x for x in u)
    cluster_mass = 6.0 / (z * D ** (-1.0 / 3.0)) ** 2 * (D * t * t) ** (1.0 / 3.0)
    return -(ramp + cluster_mass * (uniform_velocity_rate(V) - 1.5 * V * V))


def mass_density_from_grid(m, nw_pan=80, nper=16, wmax=10.0):
    """F(m) = int f(m,p) dp = int m f(m, m w) dw  (clusters per unit s per unit m)."""
    m = np.atleast_1d(np.asarray(m, dtype=float))
    w, ww = _gauss_legendre_panels(-wmax, wmax, nw_pan, nper)
    dens = joint_density_mw(m[:, None], w[None, :])
    return (dens * ww[None, :]).sum(axis=1)


def fmp_H(mu):
    """FMP (106) with b = 1: H(mu) = (1/2 pi i) int dw exp(-mu w)/Ai(w)^2, contour Re w = mu^2/4."""
    mu = np.atleast_1d(np.asarray(mu, dtype=float))
    y, yw = _gauss_legendre_panels(0.0, 40.0, 80, 16)
    out = np.empty_like(mu)
    for i, x in enumerate(mu):
        eta = 0.25 * x * x if x > 0 else 0.0
        wv = eta + 1j * y
        eai = special.airye(wv)[0]
        expo = -x * wv + (4.0 / 3.0) * wv ** 1.5 + x ** 3 / 12.0   # times exp(-mu^3/12) below
        val = (np.exp(expo) / eai ** 2).real
        out[i] = np.exp(-x ** 3 / 12.0) * (val * yw).sum() / np.pi
    return out


def mass_density_fmp(m):
    """(EB10) F(m) = m S(m) H(m/2^(1/3))  [FMP (105) mapped to our units]."""
    m = np.atleast_1d(np.asarray(m, dtype=float))
    return m * airy_zero_sum(m) * fmp_H(m / C13)


def mass_small_asymptote(m):
    """(EB11) F(m) ~ (2 pi m)^(-1/2)  [FMP (108)]."""
    return (2.0 * np.pi * np.asarray(m, float)) ** -0.5


def mass_large_asymptote(m):
    """(EB12) F(m) ~ sqrt(pi/2) m^(5/2) exp(-m^3/24 - |a_1| m/2^(1/3))  [FMP (109)].

    Measured relative correction: F/asymptote - 1 = 0.029, 0.011, 0.0054, 0.0030 at m = 5, 7, 9, 11 (~ 4/m^3)."""
    m = np.asarray(m, dtype=float)
    return np.sqrt(np.pi / 2.0) * m ** 2.5 * np.exp(-m ** 3 / 24.0 - ALPHA1 * m / C13)


def fmp_mapping():
    """How our scaled variables map onto FMP's (t = 1, rho = 1, Brownian variance 1/beta, b = (beta/2)^(1/3))."""
    return {
        "FMP_mass": "M_FMP = m / (2^(1/3) b)",
        "FMP_density": "mu_1^FMP(M_FMP) = (2^(1/3) b)^2 F(m)",
        "b=1 tail": "exp(-m^3/24) = exp(-M_FMP^3/12)",
        "our raw units": "b = (3/2)^(1/3) and M_FMP = M t^(-2/3); tail exp(-(M t^(-2/3))^3/8)",
    }


def compute_constants(D=D_SHOCKGAS, check_resolution=True):
    mom = scaled_moments()
    res = {}
    if check_resolution:
        mom2 = scaled_moments(nu_pan=60, nw_pan=120, nper=20)
        res = {k: abs(mom2[k] - mom[k]) for k in ("N_s", "K", "kurtosis", "mass_sum_rule")}
    K, Ns = mom["K"], mom["N_s"]
    kappa = K * D ** (2.0 / 3.0)
    nu = Ns * D ** (-1.0 / 3.0)
    c_tail = 1.0 / (6.0 * D)
    return dict(
        kappa=kappa, nu=nu, variance=kappa, kurtosis=mom["kurtosis"], tail_constant_c=c_tail,
        scaled=dict(N_s=Ns, K=K, mass_sum_rule=mom["mass_sum_rule"], kurtosis=mom["kurtosis"],
                    resolution_change=res),
        D=D,
    )


def _effective_tail_fit(D, zlo, zhi):
    z = np.linspace(zlo, zhi, 40)
    y = np.log(phi(z, D))
    A = np.vstack([np.ones_like(z), -z ** 3]).T
    coef = np.linalg.lstsq(A, y, rcond=None)[0]
    return float(coef[1])


def _write_table(path, header_lines, columns, names):
    with atomic_output(path, "w") as fh:
        for h in header_lines:
            fh.write("# " + h + "\n")
        fh.write("# " + " ".join(names) + "\n")
        for row in zip(*columns):
            fh.write(" ".join("%.10e" % v for v in row) + "\n")


def main(argv=None):
    ap = ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out-dir", required=True)
    ap.add_argument("--D", type=float, default=D_SHOCKGAS,
                    help="momentum variance per unit length (rho <v^2>); 1/3 for v ~ U[-1,1]")
    args = ap.parse_args(argv)
    # D sets every scale (EB2: M* = (D rho t^2)^(1/3), V* = D^(1/3) t^(-1/3), c = 1/(6D)): at 0 they
    # divide by zero, below 0 they are complex, NaN or infinite they fill the tables with NaN. Refused
    # before anything is made or written.
    if not (np.isfinite(args.D) and args.D > 0):
        ap.error("--D %r: the momentum variance per unit length of the initial velocities, rho <v^2>, must be "
                 "finite and > 0 (1/3 for v ~ U[-1, 1] at unit spacing, the default)" % args.D)
    # An --out-dir that cannot be made or written in is refused before the work (seconds of
    # quadrature), in one line; so is one that fails when written (a full disk).
    why = output_directory_problem(args.out_dir)
    if why is not None:
        ap.error(cannot_write(args.out_dir, why, "--out-dir"))
    try:
        os.makedirs(args.out_dir, exist_ok=True)
        return write_theory(args.out_dir, args.D)
    except OSError as error:
        ap.error(cannot_write(error.filename or args.out_dir, error, "--out-dir"))


def write_theory(out_dir, D):
    """Writes phi.dat, phi_tail.dat, mass_distribution.dat, constants.json and constants.gp in out_dir
    (each beside its name and renamed onto it once whole: an error leaves the previous one) and prints
    the constants."""
    const = compute_constants(D)
    kappa = const["kappa"]
    # Phi depends on z only through z / D^(1/3) (EB8), so the tables' z ranges, chosen for the paper's
    # D = 1/3, scale with (3D)^(1/3): the same points of the scaled function for every D (exactly 1 at
    # D = 1/3). With fixed ranges a D below about 0.3 ran phi_tail.dat's Phi into underflow (log Phi
    # = -inf, the local exponent NaN).
    z_scale = (3.0 * D) ** (1.0 / 3.0)

    # Phi(z)
    z = z_scale * np.linspace(-4.0, 4.0, 321)
    ph = phi(z, D)
    gauss = np.exp(-z * z / (2 * kappa)) / np.sqrt(2 * np.pi * kappa)
    var_from_table = np.trapz(z * z * ph, z)
    norm_from_table = np.trapz(ph, z)
    _write_table(os.path.join(out_dir, "phi.dat"),
                 ["Mass-weighted velocity scaling function, P(v,t) = t^(1/3) Phi(v t^(1/3)), exact sticky-gas",
                  "asymptote (python/exact_ballistic.py EB8), units: unit masses, spacing 1, v ~ U[-1,1] (D = %.6g)" % D,
                  "gauss_same_var: normal density with variance kappa = %.10f" % kappa,
                  "tail_asymptote: (EB9) 2^(11/6) D^(1/3)/Ai'(a1) z^-2 exp(-z^3/(6D) - |a1| z/(2D)^(1/3))"],
                 [z, ph, gauss, phi_tail_asymptote(z, D)],
                 ["z", "Phi", "gauss_same_var", "tail_asymptote"])

    # far tail of Phi with its local exponent gamma_loc = d ln(-ln(z^2 Phi / A)) / d ln z (A the EB9
    # prefactor), the curve the far-tail sampler is held against (docs/far-tail.md)
    zt = z_scale * np.arange(1.0, 7.0 + 1e-9, 0.05)
    lpt = np.log(phi(zt, D))
    A_tail = 2.0 ** (11.0 / 6.0) * D ** (1.0 / 3.0) / AIP1
    local = np.gradient(np.log(-(lpt + 2.0 * np.log(zt) - np.log(A_tail))), np.log(zt))
    _write_table(os.path.join(out_dir, "phi_tail.dat"),
                 ["Far tail of the exact Phi (EB8) and its local exponent d ln(-ln(z^2 Phi/A))/d ln z,",
                  "A = 2^(11/6) D^(1/3)/Ai'(a1) = %.6f (EB9); tends to 3. D = %.6g" % (A_tail, D)],
                 [zt, lpt, local, np.log(phi_tail_asymptote(zt, D))],
                 ["z", "log_phi", "local_exponent", "log_tail_asymptote"])

    # mass distribution
    m = np.concatenate([np.geomspace(1e-4, 0.1, 31)[:-1], np.linspace(0.1, 9.0, 179)])
    F = mass_density_from_grid(m)
    Ns = const["scaled"]["N_s"]
    _write_table(os.path.join(out_dir, "mass_distribution.dat"),
                 ["Scaled cluster-mass distribution of the exact sticky-gas asymptote (EB10-EB12).",
                  "m = M / M*, M* = (D t^2)^(1/3) = (t^2/3)^(1/3) for shockgas; mu_FMP = m/2^(1/3) (FMP variable, b = 1).",
                  "F = clusters per unit scaled length per unit m; clusters per particle with mass in dM: F(M/M*) dM / M*^2.",
                  "pdf_number = F/N_s (pdf of m over clusters, N_s = %.10f); pdf_mass = m F (mass-weighted pdf)." % Ns,
                  "small_asym = (2 pi m)^(-1/2); large_asym = sqrt(pi/2) m^(5/2) exp(-m^3/24 - |a1| m/2^(1/3))."],
                 [m, m / C13, F, F / Ns, m * F, mass_small_asymptote(m), mass_large_asymptote(m)],
                 ["m", "mu_FMP", "F", "pdf_number", "pdf_mass", "small_asym", "large_asym"])

    out = dict(
        kappa=kappa,
        nu=const["nu"],
        variance=kappa,
        variance_from_phi_table=var_from_table,
        phi_table_normalisation=norm_from_table,
        kurtosis=const["kurtosis"],
        tail_constant_c=const["tail_constant_c"],
        tail_form="Phi(z) ~ A z^-2 exp(-c z^3 - B z), c = 1/(6D), B = |a1|/(2D)^(1/3) = %.6f, A = 2^(11/6) D^(1/3)/Ai'(a1) = %.6f"
                  % (ALPHA1 / (2 * D) ** (1 / 3), 2 ** (11 / 6) * D ** (1 / 3) / AIP1),
        # The windows [1, 2.5] and [2, 3.5] at the paper's D, scaled with (3D)^(1/3) as the tables are.
        effective_c_fit_logPhi_vs_z3={"z in [%g,%g]" % (z_scale * lo, z_scale * hi):
                                      _effective_tail_fit(D, z_scale * lo, z_scale * hi)
                                      for lo, hi in ((1.0, 2.5), (2.0, 3.5))},
        definitions=dict(
            T="T(t) = sum_c M_c V_c^2 / N - (sum_c M_c V_c / N)^2 ~ kappa t^(-2/3)",
            n="clusters per particle n(t) ~ nu t^(-2/3)",
            Phi="P(v,t) = t^(1/3) Phi(v t^(1/3)), cluster velocities weighted by cluster mass, int Phi = 1",
            kurtosis="<z^4>/<z^2>^2 of Phi (Gaussian: 3)",
        ),
        units=dict(
            D="momentum variance per unit length = rho <v^2> = 1/3 (unit masses, spacing 1, v ~ U[-1,1])",
            scales="M* = ell = (D t^2/rho^2)^(1/3) (rho = 1), P* = sqrt(D ell), V* = ell/t = D^(1/3) t^(-1/3)",
            conversion="kappa = K D^(2/3), nu = N_s D^(-1/3), Phi(z) = D^(-1/3) P_w(z D^(-1/3)), c = 1/(6D)",
            FMP=fmp_mapping(),
        ),
        scaled=const["scaled"],
        references=dict(
            joint_density="EB3 = Frachebourg, Martin & Piasecki, Physica A 279, 69 (2000) eqs. (72), (95)-(98), (104); Frachebourg PRL 82, 1502 (1999)",
            psi="EB4 = Groeneboom, PTRF 81, 79 (1989) (g_c with hat g = (2/c)^(1/3)/Ai(i (2c^2)^(-1/3) s)); FMP (97)-(98), (101)",
            excursion="EB5 = Louchard J. Appl. Prob. 21, 479 (1984); Janson Probab. Surveys 4, 80 (2007); FMP (96)",
            mass="EB10-EB12 = FMP (105)-(109)",
            variational_principle="E, Rykov & Sinai, CMP 177, 349 (1996)",
        ),
        accuracy=("quadrature: Gauss-Legendre panels in (u = sqrt(m), w); mass sum rule holds to |1 - sum| = %.1e; "
                  "changes under grid refinement: %s" % (abs(1 - const["scaled"]["mass_sum_rule"]),
                                                          {k: "%.1e" % v for k, v in const["scaled"]["resolution_change"].items()})),
    )
    with atomic_output(os.path.join(out_dir, "constants.json"), "w") as fh:
        json.dump(out, fh, indent=2)
    # The same constants as gnuplot variables, for the figures' theory curves.
    with atomic_output(os.path.join(out_dir, "constants.gp"), "w") as fh:
        fh.write("# exact sticky-gas constants (python/exact_ballistic.py), D = %.10g\n" % D)
        for key in ("kappa", "nu", "kurtosis", "tail_constant_c"):
            fh.write("exact_%s = %.10g\n" % (key, out[key]))
    print(json.dumps({k: out[k] for k in ("kappa", "nu", "variance", "variance_from_phi_table",
                                          "kurtosis", "tail_constant_c", "effective_c_fit_logPhi_vs_z3")}, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
