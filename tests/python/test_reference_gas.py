#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""shockgas-sim against an independent plain reference, python/reference_gas.py (ctest python.reference).

    test_reference_gas.py SIM [WORK_DIR]        (SIM: the shockgas-sim program; about 7 s of CPU)

For each case an init file is written, shockgas-sim runs it (-R 1) with every engine (event,
passthrough, hybrid, exact, auto), and at every sample time the output is compared with the reference
run from the same start at the same times: clusters and collision counts exactly, T and the kinetic
energy to REL_TOL, the status, and for a collapse its time and collision count. An engine that the
documentation says cannot run a case must refuse it with its documented one-line error (exit status 2,
no output file); auto must pick the engine docs/engines.md names. The cases (CASES below, 72):
a seeded grid over N in {2, 3, 4, 7, 20, 60}, r in {0, 0.2, 0.5, 0.9, 0.99, 1}, delta in {0, 1e-3,
1e-2, 0.1, 10}, both sub-threshold mechanisms, lattice and random positions, uniform and Gaussian
velocities, ring lengths other than N and unequal masses; and hand-made edge cases (the seam,
simultaneous and triple collisions, g exactly delta, a collision exactly at a sample time, equal
velocities, r = 1, delta above every relative speed, coincident starts, collapse). What each case
is for is in its `note`. docs/reference-check.md describes the check and the mutations it catches.

Where two correct codes stop agreeing (chaos): the reference runs in 40-digit decimal arithmetic (so
its own rounding is negligible), then as probes twice more with one velocity moved by one ulp of its
double (particle 0 up, particle N/2 down), and once in doubles. A double-precision code such as
shockgas-sim makes rounding errors of about an ulp at every collision, so where a probe differs from
the reference by more than HORIZON_FRACTION * REL_TOL, or in a count, the simulator may differ by more
than REL_TOL without being wrong: from that sample on the case is not compared (its "horizon"). The
run lengths keep each case to at most EVENT_BUDGET collisions, and no case reaches its horizon (the
probes move T and K by at most 1.6e-13 relative); the summary prints how many samples were compared.
A collapse is compared (time, cluster mass, and the collision count where the probes and reduced-
precision runs of the reference agree on it) when the 1-ulp probes collapse at the same time.

SHOCKGAS_REFERENCE_GAS=path/to/reference_gas.py runs the test against another copy of the reference
(how the mutations in docs/reference-check.md were run). Exit status 0 all agree, 1 a disagreement,
77 (SKIP) without numpy or h5py.
"""
import importlib.util
import math
import os
import resource
import subprocess
import sys
import tempfile
import time
import traceback

HERE = os.path.dirname(os.path.realpath(__file__))
try:
    import h5py  # noqa: F401  (shockgas's; imported here so that its absence is a skip)
    import numpy as np
except ImportError as error:  # pragma: no cover
    print("SKIP: needs numpy and h5py (%s)" % error)
    sys.exit(77)
# python/shockgas from PYTHONPATH (ctest's): missing, the test fails rather than skips.
import shockgas  # noqa: E402

_reference_path = (os.environ.get("SHOCKGAS_REFERENCE_GAS")
                   or os.path.join(HERE, "..", "..", "python", "reference_gas.py"))
_spec = importlib.util.spec_from_file_location("reference_gas", _reference_path)
reference_gas = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(reference_gas)

if len(sys.argv) < 2:
    sys.exit(__doc__)
SIM = sys.argv[1]
WORK = sys.argv[2] if len(sys.argv) > 2 else tempfile.mkdtemp(prefix="reference_gas.")
os.makedirs(WORK, exist_ok=True)

# ----------------------------------------------------------------------------------------- tolerances
# T and the kinetic energy K: |T_sim - T_ref| <= REL_TOL * (|T_ref| + 2 K_ref) (T is a difference of two
# moments of size <v^2> = 2K, so its rounding scales with <v^2>, not with T: a drifting gas, or the
# final single cluster with T = 0, has T far below <v^2>), and |K_sim - K_ref| <= REL_TOL * K_ref.
# Where an energy vanishes (one cluster at rest, equal velocities) the scales have the floor ENERGY_FLOOR
# K(0): velocities carry rounding ~1e-16 of the initial velocity scale, so a vanishing K or T comes out
# as ~1e-32 K(0); 1e-20 K(0) is far above that and far below any energy that does not vanish here.
# Measured (docs/reference-check.md): every engine is within 3.8e-15 of the exact reference on every
# compared sample, and the reference in doubles within 3.8e-15 of itself in 40 digits. Changing r by a
# relative 1e-6 in the reference moves T or K by at least 3.0e-9 in every case with an inelastic
# collision (median 4e-6). So 1e-9 sits 10^5 above rounding and 3 times below that smallest physics error.
REL_TOL = 1e-9
ENERGY_FLOOR = 1e-20
# A sample is compared only if a 1-ulp change of one initial velocity moves the (exact) reference there by
# less than HORIZON_FRACTION * REL_TOL and changes no count. The simulator's rounding is a few ulps per
# collision at up to EVENT_BUDGET collisions, i.e. at most ~10^3 times a 1-ulp perturbation of the start.
HORIZON_FRACTION = 1e-3
# The collapse time: measured agreement 1.3e-13 relative at worst (a collapse is the limit point of a
# geometric sequence of collisions, well defined even where the count is not); compared where the 1-ulp
# probes collapse within HORIZON_FRACTION * COLLAPSE_TIME_TOL of the reference. 1e-9: REL_TOL's margin.
COLLAPSE_TIME_TOL = 1e-9
# A sample within SAMPLE_GUARD * max(1, t) of a reference event (in a case not marked exact) is skipped: there the
# event may fall on either side of the sample in two correct codes. Rounding of event times is ~1e-15 t.
SAMPLE_GUARD = 1e-9
# Run lengths: at most EVENT_BUDGET collisions (t_max falls in the widest gap between two of the last 50
# events before the budget), and at most T_CAP.
EVENT_BUDGET = 300
T_CAP = 40.0
DIGITS = 40                # the reference's decimal digits (30 and 60 agree to 8e-30 on every case)
COLLAPSE_COUNT_DIGITS = (16, 17, 20, None)   # reduced precisions (None: doubles) for the collapse count
LINEAR_SAMPLES = 12        # sample times t_max k/12 besides the simulator's log grid (10 per decade)
SEED = 20261126
# A safety stop for the reference (a broken copy of it must fail the test, not hang it): every case
# needs fewer than 2000 events, a collapse included.
MAX_REFERENCE_EVENTS = 100000

ENGINES = ("event", "passthrough", "hybrid", "exact", "auto")

# The number of collisions before a collapse (/collapse/collisions) where the final burst has four or more
# clusters: there successive collisions come closer in time than the spacing of doubles at t (collapse_n4_r01:
# 51 of its 91 intervals; gaps down to 1e-47), so the order the event engine keeps in doubles does not
# resolve them, and its count moves under a 1-ulp change of one initial velocity: 84 to 99 around the
# reference's 92 (collapse_n4_r01), 923 to 1118 around 1018 (collapse_block_r05). The reference's count does not move under those changes, nor in 16 to 60
# digits. COLLAPSE_BURST_COUNT_TOL = 0.15 (relative) covers that spread (at most 9.8%) with a margin for other
# compilers' rounding; the three-body collapses alternate between two pairs, an order rounding cannot change,
# and are compared exactly (count_tolerance 0). docs/reference-check.md, docs/cli-and-output.md (/collapse).
COLLAPSE_BURST_COUNT_TOL = 0.15


# -------------------------------------------------------------------------------------------- cases
def case(name, position, velocity, r, delta, sub="elastic", L=None, mass=None, t_max=None, samples=(),
         exact=False, note="", expect_collapse=None, constant_T=False, count_tolerance=0.0):
    """One start. exact: every number is dyadic, so times are exact and samples may sit on events."""
    n = len(position)
    return dict(name=name, position=np.asarray(position, float), velocity=np.asarray(velocity, float),
                mass=None if mass is None else np.asarray(mass, float), L=float(n if L is None else L), r=r,
                delta=delta, sub=sub, t_max=t_max, samples=tuple(samples), exact=exact, note=note,
                expect_collapse=expect_collapse, constant_T=constant_T, count_tolerance=count_tolerance)


def generated_cases():
    """The seeded grid: 6 N x 6 r, delta, mechanism, positions, velocities, L and masses varied across
    them so that each value meets several others; then unequal masses and drifting gases."""
    rng = np.random.default_rng(SEED)
    Ns, rs = (2, 3, 4, 7, 20, 60), (0.0, 0.2, 0.5, 0.9, 0.99, 1.0)
    deltas, subs = (0.0, 1e-3, 1e-2, 0.1, 10.0), ("elastic", "sticky")
    out = []

    def start(n, positions, velocities, L, drift=0.0):
        if positions == "lattice":
            x = np.arange(n) * (L / n)
        else:
            x = np.sort(rng.uniform(0.0, L, n))
        if velocities == "uniform":
            v = rng.uniform(-1.0, 1.0, n)
        else:
            v = rng.normal(0.0, math.sqrt(1.0 / 3.0), n)
        return x, v + drift

    for a, n in enumerate(Ns):
        for b, r in enumerate(rs):
            k = 6 * a + b
            delta, sub = deltas[(a + 2 * b) % 5], subs[(a + b) % 2]
            positions = ("lattice", "random")[(k // 2) % 2]
            velocities = ("uniform", "gaussian")[(a + k) % 2]
            L = n * (0.45, 1.0, 1.0, 2.5)[k % 4]
            x, v = start(n, positions, velocities, L)
            out.append(case("grid%02d" % k, x, v, r, delta, sub, L=L,
                            note="N=%d r=%g delta=%g %s, %s positions, %s velocities, L=%g" % (
                                n, r, delta, sub, positions, velocities, L)))
    # Unequal masses (integers 1-3 and reals in [0.5, 2]): the general collision rule and mass-weighted T.
    for k in range(8):
        n = (3, 4, 7, 20, 60, 7, 20, 4)[k]
        r = (0.0, 0.2, 0.5, 0.9, 0.99, 1.0, 0.5, 0.9)[k]
        delta, sub = deltas[(k + 1) % 5], subs[k % 2]
        x, v = start(n, ("lattice", "random")[k % 2], ("uniform", "gaussian")[(k // 2) % 2], float(n))
        mass = rng.integers(1, 4, n).astype(float) if k % 2 == 0 else rng.uniform(0.5, 2.0, n)
        out.append(case("mass%02d" % k, x, v, r, delta, sub, mass=mass,
                        note="unequal masses, N=%d r=%g delta=%g %s" % (n, r, delta, sub)))
    # A drifting gas (mean velocity 3): T is small against <v^2>; lab-frame K.
    for k in range(4):
        n, r, delta, sub = (7, 20, 60, 20)[k], (0.5, 0.9, 0.0, 0.99)[k], (1e-2, 0.1, 0.0, 1e-3)[k], subs[k % 2]
        L = (7.0, 13.0, 150.0, 20.0)[k]
        x, v = start(n, "random", "uniform", L, drift=3.0)
        out.append(case("drift%d" % k, x, v, r, delta, sub, L=L,
                        note="mean velocity 3, N=%d r=%g delta=%g %s L=%g" % (n, r, delta, sub, L)))
    return out


def hand_cases():
    """Edge cases, each with what it is for. Dyadic numbers where times must be exact."""
    c = []
    c.append(case("seam_pair", [0.25, 1.5], [-0.5, 0.5], 0.5, 0.1, L=2.0, samples=(0.75,), exact=True,
                  note="N=2: the only approaching pair is across the seam (gap 0.75, meet at t = 0.75, a "
                       "sample time); then both sides of the ring"))
    c.append(case("seam_chain", np.arange(7.0), [-1, 0, 0, 0, 0, 0, 1.0], 0.9, 0.01,
                  note="N=7: particles 6 and 0 meet across the seam at t = 0.5, then the pulse runs round"))
    c.append(case("seam_merge", np.arange(7.0), [-1, 0, 0, 0, 0, 0, 1.0], 0.0, 0.01, exact=True, t_max=40.0,
                  note="sticky gas: the first merge is across the seam"))
    c.append(case("seam_merge_masses", [0.5, 1.5, 2.75], [-0.5, 0.0, 0.25], 0.0, 0.0, L=3.0,
                  mass=[2.0, 1.0, 3.0], exact=True, t_max=20.0,
                  note="masses 2, 1, 3; the heavy last cluster catches the first one across the seam"))
    rng = np.random.default_rng(SEED + 1)
    c.append(case("equal_velocities", np.sort(rng.uniform(0, 20, 20)), np.full(20, 0.3), 0.9, 0.01, t_max=40.0,
                  note="all velocities equal: no collision ever, T = 0"))
    c.append(case("touching_equal_velocity", [1.0, 1.0, 3.0], [0.25, 0.25, -0.5], 0.5, 0.1, L=4.0, exact=True,
                  t_max=10.0, note="two particles at one point with equal velocities do not collide"))
    c.append(case("coincident_start", [1.0, 1.0, 2.0], [0.5, -0.5, 0.0], 0.5, 0.1, L=3.0, exact=True,
                  t_max=10.0, note="two particles start at one point approaching: they collide at t = 0, and "
                                   "the t = 0 sample holds that collision (state after every event at time <= t)"))
    c.append(case("simultaneous_pairs", [1.0, 2.0, 5.0, 6.0], [0.5, -0.5, 0.5, -0.5], 0.5, 0.1, L=8.0,
                  exact=True, t_max=20.0, samples=(9.0,),
                  note="two disjoint pairs collide at t = 1 (a sample time), then two more at t = 9 (one "
                       "across the seam), each a sample time"))
    c.append(case("simultaneous_pairs_sticky", [1.0, 2.0, 5.0, 6.0], [0.5, -0.5, 0.5, -0.5], 0.0, 0.1, L=8.0,
                  exact=True, t_max=20.0, note="two merges at t = 1 at once"))
    c.append(case("triple_elastic", [3.0, 4.0, 5.0], [1.0, 0.0, -1.0], 1.0, 0.1, L=8.0, exact=True, t_max=20.0,
                  samples=(1.0, 5.0), constant_T=True,
                  note="three particles meet at one point at t = 1: three exchanges whatever the order"))
    c.append(case("g_equals_delta", [1.0, 2.0], [0.25, -0.25], 0.5, 0.5, "sticky", L=4.0, exact=True, t_max=10.0,
                  note="relative speed exactly delta is inelastic (g >= delta), not a sticky merge"))
    c.append(case("g_below_delta", [1.0, 2.0], [0.25, -0.25], 0.5, float(np.nextafter(0.5, 1.0)), "sticky",
                  L=4.0, exact=True, t_max=10.0, note="relative speed one ulp below delta: sticky merge"))
    c.append(case("sticky_to_one_cluster", np.arange(4.0), [0.75, -0.25, 0.5, -1.0], 0.0, 0.0,
                  t_max=100.0, note="sticky gas down to one cluster (T = 0)"))
    c.append(case("two_body_elastic_ring", [0.0, 1.0], [0.7, -0.3], 1.0, 0.0, L=2.0, t_max=150.0, constant_T=True,
                  note="N=2, r = 1, delta = 0: collisions on both sides of the ring, 75 of them"))
    rng = np.random.default_rng(SEED + 2)
    x, v = np.sort(rng.uniform(0, 20, 20)), rng.uniform(-1, 1, 20)
    c.append(case("r_equals_1", x, v, 1.0, 0.01, constant_T=True, note="r = 1: energy conserved, T constant"))
    c.append(case("delta_above_all_elastic", x, v, 0.5, 10.0, "elastic", constant_T=True,
                  note="delta = 10 above every relative speed: a purely elastic gas whatever r"))
    c.append(case("delta_above_all_sticky", x, v, 0.5, 10.0, "sticky",
                  note="delta = 10 above every relative speed, sticky: the sticky gas whatever r"))
    c.append(case("dense_ring", np.sort(rng.uniform(0, 2.5, 7)), rng.uniform(-1, 1, 7), 0.9, 0.01, L=2.5,
                  note="N = 7 on a ring of length 2.5"))
    c.append(case("dilute_ring", np.sort(rng.uniform(0, 40, 7)), rng.uniform(-1, 1, 7), 0.2, 1e-3, L=40.0,
                  note="N = 7 on a ring of length 40"))
    # Inelastic collapse (delta = 0): the run stops at an inelastic collision slower than 1e-12.
    block = 6.0 + 0.1 * (np.arange(10) - 5)
    rng = np.random.default_rng(SEED + 3)
    c.append(case("collapse_block_r05", np.concatenate([[0.5], block[1:-1], [11.5]]),
                  np.concatenate([[1.0], rng.uniform(-0.01, 0.01, 8), [-1.0]]), 0.5, 0.0, L=12.0, t_max=12.0,
                  expect_collapse=True, count_tolerance=COLLAPSE_BURST_COUNT_TOL, note="N=10, r = 0.5: a block at rest struck from both sides collapses"))
    c.append(case("collapse_3body_r05", [0.5, 1.25, 2.5], [0.5, 0.0, -0.5], 0.5, 0.0, L=3.0, mass=[30.0, 1.0, 30.0],
                  t_max=3.0, samples=(2.0, 2.03), expect_collapse=True,
                  note="N=3, r = 0.5: a light particle between two heavy ones (masses 30, 1, 30) collapses"))
    c.append(case("collapse_3body_r09", [0.5, 1.25, 2.5], [0.5, 0.0, -0.5], 0.9, 0.0, L=3.0,
                  mass=[1000.0, 1.0, 1000.0], t_max=3.0, samples=(1.9, 2.0), expect_collapse=True,
                  note="N=3, r = 0.9 (masses 1000, 1, 1000): ~1200 collisions, gaps far below the spacing of "
                       "doubles near the positions"))
    # Cooling is not collapse: two particles alone, and three above the three-body threshold r = 7 - 4 sqrt 3,
    # lose relative speed geometrically, g < 1e-12 by t ~ 1e12, but never collide infinitely often in finite
    # time: shockgas-sim must not report them "collapsed".
    c.append(case("cooling_pair_r05", [0.0, 1.0], [0.75, -0.25], 0.5, 0.0, L=2.0, t_max=1e14,
                  expect_collapse=False, note="N=2, r = 0.5, delta = 0: Haff cooling to g ~ 1e-14, no collapse"))
    c.append(case("cooling_triple_r05", [0.0, 1.0, 2.5], [0.6, -0.1, -0.5], 0.5, 0.0, L=4.0, t_max=1e14,
                  expect_collapse=False, note="N=3, r = 0.5 > 7 - 4 sqrt 3, delta = 0: no collapse"))
    rng = np.random.default_rng(9)   # the third of seeds 0, 1, ... whose start collapses before t = 40
    c.append(case("collapse_random_r05", np.sort(rng.uniform(0, 10, 10)), rng.uniform(-1, 1, 10), 0.5, 0.0,
                  t_max=12.0, expect_collapse=True, count_tolerance=COLLAPSE_BURST_COUNT_TOL, note="N=10, r = 0.5, random start: collapses at t = 8.97"))
    rng = np.random.default_rng(2)
    c.append(case("collapse_n4_r01", np.sort(rng.uniform(0, 4, 4)), rng.uniform(-1, 1, 4), 0.1, 0.0, t_max=5.0,
                  expect_collapse=True, count_tolerance=COLLAPSE_BURST_COUNT_TOL, note="N=4, r = 0.1: collapses at t = 3.027 after 92 collisions, 51 of "
                                             "the intervals between them shorter than the spacing of doubles at t"))
    return c


CASES = generated_cases() + hand_cases()


# ------------------------------------------------------------------------------------ engine rules
def engine_refusal(engine, c):
    """None if the documentation says `engine` runs case c, else the fragments one of which its error
    line must contain (docs/engines.md, docs/passthrough-engine.md, docs/exact-engine.md)."""
    equal_masses = c["mass"] is None or bool(np.all(c["mass"] == c["mass"][0]))
    if engine == "exact":
        return None if c["r"] == 0 else ["--engine exact solves only the sticky gas r = 0"]
    if engine in ("passthrough", "hybrid"):
        head = "--engine %s cannot run this: " % engine
        reasons = []
        if c["r"] == 0:
            reasons.append(head + "r = 0 is the sticky gas")
        if c["delta"] == 0:
            reasons.append(head + "delta = 0 puts no collision below the threshold")
        if c["sub"] == "sticky":
            reasons.append(head + "sticky sub-threshold collisions merge particles")
        if not equal_masses:
            reasons.append(head + "unequal masses")
        return reasons or None
    return None


def auto_engine(c):
    if c["r"] == 0:
        return "exact"
    return "hybrid" if engine_refusal("passthrough", c) is None else "event"


# ------------------------------------------------------------------------------------------ reference
def reference(c, times, velocity=None, digits=DIGITS, max_events=MAX_REFERENCE_EVENTS):
    return reference_gas.simulate(c["position"], c["velocity"] if velocity is None else velocity, c["mass"],
                                  c["L"], c["r"], c["delta"], c["sub"], 1e-12, times, max_events=max_events,
                                  digits=digits)


def choose_t_max(c):
    if c["t_max"] is not None:
        return c["t_max"]
    probe = reference(c, [T_CAP], max_events=EVENT_BUDGET)
    events = probe.event_times
    if len(events) < EVENT_BUDGET or probe.status == "collapsed":
        return T_CAP
    k = max(range(EVENT_BUDGET - 50, EVENT_BUDGET - 1), key=lambda i: events[i + 1] - events[i])
    return 0.5 * (events[k] + events[k + 1])


def scales(ref, k):
    """(scale of T, scale of K) at sample k: |T| + 2K and K, each with the floor ENERGY_FLOOR K(0)."""
    floor = ENERGY_FLOOR * ref.kinetic_energy[0]
    return abs(ref.temperature[k]) + 2 * ref.kinetic_energy[k] + 2 * floor, ref.kinetic_energy[k] + floor


def relative_errors(ref, k, T, K):
    scale_T, scale_K = scales(ref, k)
    return abs(T - ref.temperature[k]) / scale_T, abs(K - ref.kinetic_energy[k]) / scale_K


def differs(a, b, k, fraction):
    """Whether evolutions a (the reference) and b differ at sample k by more than fraction * the tolerances."""
    ta, tb = a.temperature[k], b.temperature[k]
    if math.isnan(ta) or math.isnan(tb):
        return math.isnan(ta) != math.isnan(tb)
    if a.clusters[k] != b.clusters[k] or a.collisions[k] != b.collisions[k]:
        return True
    return max(relative_errors(a, k, tb, b.kinetic_energy[k])) > fraction * REL_TOL


def guarded(c, times, ref):
    """Samples within SAMPLE_GUARD of a reference event (never in exact cases, whose times are exact)."""
    if c["exact"]:
        return set()
    return {k for k, t in enumerate(times)
            if any(abs(e - t) <= SAMPLE_GUARD * max(1.0, t) for e in ref.event_times)}


def horizon(c, times, ref, skip):
    """(first sample not compared, probes). Probes: the reference with one initial velocity moved by
    one ulp (particle 0 up, particle N/2 down), in DIGITS digits: how far the exact dynamics amplify a
    rounding error; and the reference in doubles: a double-precision code's own rounding during the run.
    The horizon is the first sample (outside `skip`) at which a probe differs from the reference by
    more than HORIZON_FRACTION of the tolerances, or in a count. Exact cases have no horizon."""
    probes = []
    for index, direction in ((0, math.inf), (len(c["velocity"]) // 2, -math.inf)):
        v = c["velocity"].copy()
        v[index] = np.nextafter(v[index], direction)
        probes.append(reference(c, times, velocity=v))
    if c["exact"]:
        return len(times), probes
    probes_in_doubles = probes + [reference(c, times, digits=None)]
    for k in range(len(times)):
        if k not in skip and any(differs(ref, p, k, HORIZON_FRACTION) for p in probes_in_doubles):
            return k, probes
    return len(times), probes


def collapse_is_stable(ref, probes):
    """Whether the collapse time is well defined: the 1-ulp probes collapse at the same time, to
    HORIZON_FRACTION * COLLAPSE_TIME_TOL (a collapse is a limit point of collision times)."""
    if ref.status != "collapsed":
        return False
    for p in probes:
        if p.status != "collapsed":
            return False
        if abs(p.collapse["time"] - ref.collapse["time"]) > HORIZON_FRACTION * COLLAPSE_TIME_TOL * ref.collapse["time"]:
            return False
    return True


def collapse_count_is_reproducible(c, times, ref, probes):
    """Whether the reference's collision count at collapse is robust: the 1-ulp probes and runs of the
    reference in COLLAPSE_COUNT_DIGITS digits and in doubles all give it."""
    runs = probes + [reference(c, times, digits=d) for d in COLLAPSE_COUNT_DIGITS]
    return all(p.status == "collapsed" and p.collapse["collisions"] == ref.collapse["collisions"] for p in runs)


# ------------------------------------------------------------------------------------------ running
def run_sim(c, engine, init, t_max, out):
    if os.path.exists(out):
        os.remove(out)
    extra = sorted(set([t_max * k / LINEAR_SAMPLES for k in range(1, LINEAR_SAMPLES)] + list(c["samples"])))
    extra = [t for t in extra if 0 < t < t_max]
    command = [SIM, "--init", init, "-R", "1", "-r", repr(float(c["r"])), "-d", repr(float(c["delta"])),
               "--subthreshold", c["sub"], "-t", repr(float(t_max)), "--engine", engine, "-j", "1", "-q",
               "--checkpoint-interval", "0", "--progress-interval", "0", "-o", out]
    if extra:
        command += ["--sample-times", ",".join(repr(float(t)) for t in extra)]
    done = subprocess.run(command, capture_output=True, text=True)
    return command, done


def reproducer(c, command):
    lines = ["init file: position=%r velocity=%r mass=%r ring_length=%r" % (
        c["position"].tolist(), c["velocity"].tolist(), None if c["mass"] is None else c["mass"].tolist(), c["L"]),
        "command: " + " ".join(command)]
    return "\n      ".join(lines)


class Stats:
    def __init__(self):
        self.samples = self.compared = self.guarded = 0
        self.runs, self.refusals, self.switched = {}, {}, 0
        self.worst = {}            # engine -> (relative error, case, time)
        self.collapse_times = self.collapse_counts = 0
        self.worst_collapse_time = 0.0
        self.kinds = {}            # the reference's events by rule, over all cases


def compare_run(c, engine, run, times, ref, cut, skip, stable, count_ok, stats):
    """The disagreements of one simulator run, as (kind, message)."""
    bad = []
    n = len(c["position"])
    for k, t in enumerate(times[:cut]):
        if k in skip:
            stats.guarded += 1
            continue
        stats.compared += 1
        kind = "sample at t=0" if t == 0 else "sample"
        T, K = float(run.temperature[0][k]), float(run.kinetic_energy[0][k])
        clusters, collisions = float(run.clusters[0][k]), float(run.collisions_per_particle[0][k]) * n
        if math.isnan(ref.temperature[k]):
            if not all(math.isnan(u) for u in (T, K, clusters, collisions)):
                bad.append((kind, "t=%r: the reference has collapsed (NaN), the simulator has T=%r clusters=%r"
                            % (t, T, clusters)))
            continue
        error_T, error_K = relative_errors(ref, k, T, K)
        scale = scales(ref, k)[0]
        if max(error_T, error_K) > stats.worst.get(engine, (0,))[0]:
            stats.worst[engine] = (max(error_T, error_K), c["name"], t)
        # Collision counts are compared exactly: collisions_per_particle * N must be the integer count (up to
        # the rounding of count / N and back, ~1e-13; an error of one collision is 1).
        if (clusters != ref.clusters[k] or abs(collisions - ref.collisions[k]) > 1e-9 * n
                or not error_T <= REL_TOL or not error_K <= REL_TOL):
            bad.append((kind, "t=%r: simulator T=%.17g K=%.17g clusters=%g collisions=%.10g; reference T=%.17g "
                              "K=%.17g clusters=%d collisions=%d" % (t, T, K, clusters, collisions, ref.temperature[k],
                                                                    ref.kinetic_energy[k], ref.clusters[k],
                                                                    ref.collisions[k])))
        if c["constant_T"] and not abs(T - float(run.temperature[0][0])) <= REL_TOL * scale:
            bad.append(("sample", "t=%r: T=%.17g, not the initial %.17g (energy must be conserved)"
                        % (t, T, run.temperature[0][0])))
    status = int(run.realization_status[0])
    if cut == len(times) and ref.status == "complete":
        if status != 0 or run.attrs["status"] != "complete":
            bad.append(("status", "status %d (%s); the reference completes" % (status, run.attrs["status"])))
        elif run.attrs["total_collisions"] != ref.collisions[-1]:
            bad.append(("status", "total_collisions %d; the reference %d" % (run.attrs["total_collisions"],
                                                                            ref.collisions[-1])))
    if stable:
        collapse = run.collapse
        if status != 1 or run.attrs["status"] != "collapsed" or collapse is None:
            bad.append(("collapse", "no collapse recorded (status %d); the reference collapses at t=%r after %d "
                                    "collisions" % (status, ref.collapse["time"], ref.collapse["collisions"])))
        else:
            t_c, hits = float(collapse["time"][0]), int(collapse["collisions"][0])
            speed = float(collapse["relative_speed"][0])
            stats.collapse_times += 1
            stats.worst_collapse_time = max(stats.worst_collapse_time,
                                            abs(t_c - ref.collapse["time"]) / ref.collapse["time"])
            mass = float(collapse["cluster_mass"][0])
            if (not abs(t_c - ref.collapse["time"]) <= COLLAPSE_TIME_TOL * ref.collapse["time"] or not speed < 1e-12
                    or mass != ref.collapse["cluster_mass"]):
                bad.append(("collapse", "collapse at t=%.17g, relative speed %.3g, cluster mass %g; reference t=%.17g, "
                                        "%.3g, %g" % (t_c, speed, mass, ref.collapse["time"],
                                                      ref.collapse["relative_speed"], ref.collapse["cluster_mass"])))
            if count_ok:
                stats.collapse_counts += 1
                if abs(hits - ref.collapse["collisions"]) > c["count_tolerance"] * ref.collapse["collisions"]:
                    bad.append(("collapse count", "collapse after %d collisions (at t=%.17g); the reference after "
                                                  "%d (at t=%.17g)" % (hits, t_c, ref.collapse["collisions"],
                                                                      ref.collapse["time"])))
    return bad


def check_case(c, stats, failures):
    name = c["name"]
    init = os.path.join(WORK, name + ".init.h5")
    shockgas.write_initial_condition(init, c["position"], c["velocity"], mass=c["mass"], ring_length=c["L"],
                                     overwrite=True)  # a rerun in the same work directory
    t_max = choose_t_max(c)
    ref = times = None
    cut, skip, stable, count_ok = 0, set(), False, False
    problems = []       # (engine, kind, message)
    for engine in ENGINES:
        out = os.path.join(WORK, "%s.%s.h5" % (name, engine))
        command, done = run_sim(c, engine, init, t_max, out)
        refusal = engine_refusal(engine, c)
        errors = [line for line in done.stderr.splitlines() if line.strip() and ": progress:" not in line]
        if refusal is not None:
            stats.refusals[engine] = stats.refusals.get(engine, 0) + 1
            ok = (done.returncode == 2 and len(errors) == 1 and errors[0].startswith("shockgas-sim: error: ")
                  and any(fragment in errors[0] for fragment in refusal) and not os.path.exists(out))
            if not ok:
                problems.append((engine, "refusal", "expected the documented refusal (%s), got exit %d, stderr %r"
                                 % (" | ".join(refusal), done.returncode, done.stderr.strip())))
            continue
        if done.returncode != 0:
            problems.append((engine, "exit", "exit %d: %s\n      %s" % (done.returncode, done.stderr.strip(),
                                                                     reproducer(c, command))))
            continue
        stats.runs[engine] = stats.runs.get(engine, 0) + 1
        run = shockgas.read_run(out)
        expected_engine = auto_engine(c) if engine == "auto" else engine
        if run.attrs["engine"] != expected_engine:
            problems.append((engine, "engine", "ran the %s engine, expected %s" % (run.attrs["engine"],
                                                                                   expected_engine)))
        if times is None:
            times = [float(t) for t in run.time]
            ref = reference(c, times)
            for kind, count in ref.event_kinds.items():
                stats.kinds[kind] = stats.kinds.get(kind, 0) + count
            skip = guarded(c, times, ref)
            cut, probes = horizon(c, times, ref, skip)
            stable = collapse_is_stable(ref, probes)
            count_ok = stable and collapse_count_is_reproducible(c, times, ref, probes)
            if ref.status == "stopped":
                problems.append(("reference", "reference", "did not reach t_max in %d events" % MAX_REFERENCE_EVENTS))
            if c["expect_collapse"] is not None and (ref.status == "collapsed") != c["expect_collapse"]:
                problems.append(("reference", "reference", "expected %s, got %s" % (
                    "a collapse" if c["expect_collapse"] else "no collapse", ref.status)))
        elif [float(t) for t in run.time] != times:
            problems.append((engine, "times", "sample times differ from the event engine's"))
            continue
        if engine == "hybrid" and math.isfinite(run.engine_switch_time[0]):
            stats.switched += 1
        bad = compare_run(c, engine, run, times, ref, cut, skip, stable, count_ok, stats)
        for kind in sorted({kind for kind, _ in bad}):
            first = [message for k, message in bad if k == kind]
            problems.append((engine, kind, "%d disagreement(s), first: %s\n      %s" % (
                len(first), first[0], reproducer(c, command))))
    if times is not None:
        stats.samples += len(times)
    collapse_note = ""
    if ref is not None and ref.collapse is not None:
        collapse_note = ", collapse at t=%.6g after %d (%s)" % (
            ref.collapse["time"], ref.collapse["collisions"], ("time and count compared" if c["count_tolerance"] == 0 else
            "time compared, count within %g" % c["count_tolerance"]) if count_ok else
            "time compared" if stable else "beyond the horizon")
    print(("FAIL  " if problems else "ok    ") + "%-26s N=%-3d r=%-4g delta=%-5g %-7s t_max=%-7.4g events=%-5s "
          "compared %2d/%2d%s" % (name, len(c["position"]), c["r"], c["delta"], c["sub"], t_max,
                                  "-" if ref is None else len(ref.event_times), cut,
                                  0 if times is None else len(times), collapse_note), flush=True)
    for engine, kind, message in problems:
        print("     %s: %s: %s" % (engine, kind, message))
        failures.append((name, engine, kind))


def main():
    start = time.process_time()
    stats, failures = Stats(), []
    for c in CASES:
        try:
            check_case(c, stats, failures)
        except Exception:  # a crash is a failure of that case; go on with the others
            print("FAIL  %s: crashed:\n%s" % (c["name"], traceback.format_exc()))
            failures.append((c["name"], "-", "crash"))
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = time.process_time() - start + children.ru_utime + children.ru_stime
    print("\n%d cases; simulator runs: %s; documented refusals checked: %s; hybrid runs that switched engine: %d"
          % (len(CASES), ", ".join("%s %d" % kv for kv in sorted(stats.runs.items())),
             ", ".join("%s %d" % kv for kv in sorted(stats.refusals.items())), stats.switched))
    print("sample times: %d over the cases; (sample, engine run) pairs compared: %d, skipped as within %.0e of an "
          "event: %d; collapse times compared: %d, collapse counts: %d"
          % (stats.samples, stats.compared, SAMPLE_GUARD, stats.guarded, stats.collapse_times, stats.collapse_counts))
    print("the reference's collisions: %s" % ", ".join("%d %s" % (v, k) for k, v in stats.kinds.items()))
    for engine, (error, name, t) in sorted(stats.worst.items()):
        print("largest relative difference of T or K, %-11s %.2e (%s, t=%.6g); tolerance %.0e" % (
            engine, error, name, t, REL_TOL))
    print("largest relative difference of a collapse time: %.2e; tolerance %.0e" % (
        stats.worst_collapse_time, COLLAPSE_TIME_TOL))
    print("CPU: %.1f s (this process and the simulator runs)" % cpu)
    if failures:
        print("\n%d disagreements in %d cases" % (len(failures), len({f[0] for f in failures})))
        return 1
    print("all agree")
    return 0


if __name__ == "__main__":
    sys.exit(main())
