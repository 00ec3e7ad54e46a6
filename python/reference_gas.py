#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A plain event-driven reference for the inelastic gas on a ring, written from the physics alone.

    /usr/bin/python3 python/reference_gas.py INIT.h5 -r 0.9 -d 0.01 --subthreshold elastic --t-max 10
    /usr/bin/python3 python/reference_gas.py INIT.h5 --compare RUN.h5   (the run's parameters and times)

(Debian's /usr/bin/python3: reading HDF5 needs numpy and h5py, which another python3 on the PATH may
lack; then it says which module is missing, in one line, and exits with status 2. --compare refuses
a run whose init_file_sha256 is not this file's SHA-256.)

It is an independent check of shockgas-sim (tests/python/test_reference_gas.py, ctest
`python.reference`; docs/reference-check.md): nothing in it comes from the C++ engines. It is slow
(O(N) work per collision) and meant for N up to about a hundred and a few thousand collisions.

The model (Ben-Naim, Chen, Doolen & Redner, PRL 83, 4069 (1999))
-----------------------------------------------------------------
Point particles (later: clusters) move freely on a ring of length L. Only ring neighbours can meet.
When a left cluster (mass m1, velocity v1) reaches its right neighbour (m2, v2) with closing speed
g = v1 - v2 > 0, one of three things happens:

* inelastic collision, if g >= delta (the paper's velocity threshold): the relative velocity is
  reversed and multiplied by the restitution coefficient r = 1 - 2 eps, momentum is conserved:
      v1' = v1 - (1 + r) m2/(m1 + m2) g,     v2' = v2 + (1 + r) m1/(m1 + m2) g.
  For unit masses this is the paper's collision rule, Eq. (1): the faster velocity loses the fraction
  (1 - eps) of g; read with the two labels exchanged, each velocity moves towards the other by eps g,
  v -> v - eps (v - u), the form docs/model.md quotes. It removes (1 - r^2) g^2 / 4 = eps (1 - eps) g^2
  of kinetic energy per unit-mass pair. r = 0 is the sticky gas: the pair merges into one cluster of
  mass m1 + m2 and velocity (m1 v1 + m2 v2)/(m1 + m2), whatever g and delta (ballistic aggregation,
  the paper's asymptotic universality class);
* sub-threshold collision, if g < delta: either elastic (the rule above with r = 1; for equal masses
  the two velocities are exchanged, exactly) or sticky (the pair merges, as for r = 0);
* delta = 0 and r > 0 is the pure inelastic gas, which undergoes inelastic collapse (infinitely many
  collisions in finite time; the paper's introduction and its t_stick ~ eps^(-3/2) argument). As in
  shockgas-sim, collapse is declared at an inelastic collision (g >= delta, r > 0) slower than
  `collapse_speed` with three or more clusters in contact; that realization then stops: samples at t >= the collapse time are NaN (see
  "Collapse" below).

Observables at a sample time t (the state after every event at time <= t), per docs/model.md:
  M = sum m (the total mass, N for unit masses),
  kinetic energy  K = sum m v^2 / (2 M)                 (lab frame, per unit mass),
  temperature     T = sum m v^2 / M - (sum m v / M)^2    (mass-weighted over clusters, mean removed:
                                                         the paper's T = <v^2> - <v>^2, whose
                                                         regimes are its Eq. (3)),
  clusters        number of live clusters (N minus merges),
  collisions per particle = every collision event so far (inelastic, elastic and merges) / N,
                            with N the number of particles at t = 0.
Sums are math.fsum (correctly rounded), so T and K do not depend on the order of the clusters.

How the reference works (deliberately simple)
---------------------------------------------
The state is, in ring order, each cluster's velocity and mass and the gap from it to its right
neighbour (the last cluster's gap runs across the seam to the first: the gaps add up to L). Ring
order never changes (clusters cannot pass each other), so there are no positions, windings or seam
coordinates to keep: the seam pair is the pair (last, first), like any other. Each event:
  1. for every approaching pair (g > 0) its gap closes after gap/g (a gap that rounding left
     negative closes at once, after 0); take the smallest such waiting time w (ties: below);
  2. every sample time before t + w gets the current state; a sample at exactly t + w waits for the
     event (the state at t includes every event at time <= t);
  3. every gap moves by -(v_left - v_right) w; the colliding pair's gap is set to exactly 0, which
     it is in exact arithmetic; t becomes t + w;
  4. the collision rule above. A merged cluster takes the right member's gap; across the seam it
     becomes the first cluster of the list.
Advancing gaps by waiting times, never by differences of absolute times or positions, keeps tiny
gaps accurate to their own precision: just before a collapse gaps reach 1e-47 and collisions come
closer in time than the spacing of doubles at t (the test's case collapse_n4_r01).

`digits` runs the same steps in decimal arithmetic (Python's decimal module) with that many
significant digits, every input taken as the exact value of its double; with 40 digits the rounding
of the reference is negligible for every case of its test (30 digits already give the same results).

Simultaneous collisions: pairs whose waiting times are equal are taken in list order, (i, i+1)
before (j, j+1) for i < j, the seam pair (last, first) last; the list starts at the cluster holding
particle 0. After each one the waiting times are computed afresh, so a pair that a processed
collision has turned away is not collided, and a pair that now touches while approaching (gap 0)
collides at the same time, after 0. For disjoint pairs (no common cluster) the order does not matter.
Where three clusters meet at one point the outcome can depend on the order; for equal masses and
elastic collisions it does not (three exchanges, whatever the order), and neither does it for merges.

Collapse: at an inelastic collision (g >= delta, r > 0) with g < collapse_speed, where the run of
neighbours around the pair whose gaps are below 1e-6 of the mean spacing L/N has three or more
clusters (two alone cannot collapse: a slow pair on a small ring at delta = 0 is a cooled gas), the
run stops at that time t_c, as shockgas-sim does (docs/haff-and-collapse.md). `collapse` then holds t_c, g, the number
of collisions before that one (it is not counted or processed: shockgas-sim's /collapse/collisions
counts the same way), the pair, and the collapsing cluster's mass (that run's). Samples at t < t_c are the state before that
collision, samples at t >= t_c are NaN, as in shockgas-sim's time series. Its second criterion (a
stall: max(10^6, 10 N) events advancing time by less than 10^-12 max(1, t)) is not reproduced: it
needs 10^6 events.

The result of `simulate` also carries the time of every event, so that a caller can tell whether a
sample time lies within rounding of an event (then two correct codes may disagree on whether that
event is included), and the number of events by rule (inelastic, elastic, merge).
"""
import decimal
import math
import sys

COMPLETE, COLLAPSED, STOPPED = "complete", "collapsed", "stopped"


class Evolution:
    """What `simulate` returns. Lists, one entry per sample time (in the order given):
    time, temperature, kinetic_energy, clusters, collisions (events so far), collisions_per_particle.
    status: "complete", "collapsed" or "stopped" (at max_events); collapse: None or a dict (time,
    relative_speed, collisions, pair, cluster_mass); event_times: the time of every event processed; event_kinds: how many were
    inelastic, elastic (sub-threshold) and merges; particles: N; total_mass: M."""

    def __init__(self, **fields):
        self.__dict__.update(fields)

    def __repr__(self):
        return "<Evolution %s, %d events, %d samples>" % (self.status, len(self.event_times), len(self.time))


def observables(velocity, mass, total_mass, total=math.fsum):
    """(T, K) of clusters with these velocities and masses: mass-weighted, M the total mass. `total`
    sums a sequence (math.fsum: correctly rounded, so the order of the clusters does not matter)."""
    momentum = total(m * v for m, v in zip(mass, velocity))
    twice_energy = total(m * v * v for m, v in zip(mass, velocity))
    mean = momentum / total_mass
    mean_square = twice_energy / total_mass
    return mean_square - mean * mean, twice_energy / (2 * total_mass)


def simulate(position, velocity, mass=None, ring_length=None, restitution=0.9, threshold=0.01,
             subthreshold="elastic", collapse_speed=1e-12, sample_times=(0.0,), max_events=None, digits=None):
    """Runs the gas from t = 0 and returns an Evolution at each of `sample_times`.

    position: N non-decreasing values in [0, L) (ring order); velocity: N; mass: N (default 1);
    ring_length: L (default N); restitution r in [0, 1]; threshold delta >= 0; subthreshold
    "elastic" or "sticky"; collapse_speed: see the module's docstring. max_events: stop after this
    many events (the remaining samples are NaN); None: no limit.
    digits: None computes in doubles; a number computes in decimal floating point with that many
    significant digits (Python's decimal module), every input taken as the exact value of its double:
    about 4 times slower, and free of rounding for practical purposes at 40 digits (the test's choice).
    Results (T, K, times) are returned as doubles either way.
    """
    with decimal.localcontext() as context:
        if digits is not None:
            context.prec = int(digits)
            return _simulate(position, velocity, mass, ring_length, restitution, threshold, subthreshold,
                             collapse_speed, sample_times, max_events,
                             lambda u: decimal.Decimal(float(u)), decimal.Decimal("Infinity"),
                             lambda terms: sum(terms, decimal.Decimal(0)))
        return _simulate(position, velocity, mass, ring_length, restitution, threshold, subthreshold,
                         collapse_speed, sample_times, max_events, float, math.inf, math.fsum)


def _simulate(position, velocity, mass, ring_length, restitution, threshold, subthreshold, collapse_speed,
              sample_times, max_events, number, infinity, total):
    n = len(position)
    if n < 2 or len(velocity) != n or (mass is not None and len(mass) != n):
        raise ValueError("need N >= 2 positions and as many velocities (and masses)")
    if subthreshold not in ("elastic", "sticky"):
        raise ValueError("subthreshold must be elastic or sticky, got %r" % (subthreshold,))
    zero, one = number(0), number(1)
    r, delta, slow = number(restitution), number(threshold), number(collapse_speed)
    if not zero <= r <= one or delta < zero:
        raise ValueError("need 0 <= r <= 1 and delta >= 0")
    L = number(n if ring_length is None else ring_length)
    x = [number(p) for p in position]
    if any(b < a for a, b in zip(x, x[1:])) or x[0] < zero or x[-1] >= L:
        raise ValueError("positions must be non-decreasing in [0, L)")
    # gap[i]: from cluster i to its right neighbour (i + 1, or 0 across the seam for the last one).
    gap = [x[i + 1] - x[i] for i in range(n - 1)] + [x[0] + L - x[n - 1]]
    v = [number(u) for u in velocity]
    m = [one] * n if mass is None else [number(u) for u in mass]
    total_mass = total(m)
    samples = [number(s) for s in sample_times]
    order = sorted(range(len(samples)), key=lambda k: samples[k])
    nan = float("nan")
    out = {name: [nan] * len(samples) for name in ("temperature", "kinetic_energy", "clusters", "collisions")}
    state = {"events": 0}
    kinds = {"inelastic": 0, "elastic": 0, "merge": 0}    # events by rule

    def record(k):
        T, K = observables(v, m, total_mass, total)
        out["temperature"][k], out["kinetic_energy"][k] = float(T), float(K)
        out["clusters"][k], out["collisions"][k] = len(v), state["events"]

    t, next_sample = zero, 0
    status, collapse, event_times = COMPLETE, None, []
    while True:
        # The approaching neighbour pair whose gap closes first; ties keep the first in list order.
        K = len(v)
        wait, best_i = infinity, -1
        if K >= 2:
            for i in range(K):
                g = v[i] - v[i + 1 if i + 1 < K else 0]
                if g > zero:
                    closes = gap[i] / g if gap[i] > zero else zero   # a gap rounded below 0 closes now
                    if closes < wait:
                        wait, best_i = closes, i
        when = t + wait
        while next_sample < len(order) and samples[order[next_sample]] < when:
            record(order[next_sample])
            next_sample += 1
        if next_sample == len(order) or wait == infinity:
            break
        if max_events is not None and state["events"] >= max_events:
            status = STOPPED
            break
        # Free flight to the collision of clusters i (left) and j (right) at time `when`.
        i = best_i
        j = i + 1 if i + 1 < K else 0
        for k in range(K):
            gap[k] = gap[k] - (v[k] - v[k + 1 if k + 1 < K else 0]) * wait
        gap[i] = zero
        t = when
        g = v[i] - v[j]
        m1, m2 = m[i], m[j]
        if g >= delta and r > zero and g < slow:
            # The cluster in contact: the run of neighbours around the pair whose gaps are below 1e-6 of
            # the mean spacing L/N (docs/haff-and-collapse.md).
            members, close = {i, j}, number(1e-6) * L / n
            k = i
            while len(members) < K and gap[(k - 1) % K] < close:
                k = (k - 1) % K
                members.add(k)
            k = j
            while len(members) < K and gap[k] < close:
                k = (k + 1) % K
                members.add(k)
            # Inelastic collapse needs three bodies in contact (a slow pair alone is a cooled gas): stop
            # here, without counting this collision (as /collapse/collisions).
            if len(members) >= 3:
                status = COLLAPSED
                collapse = {"time": float(t), "relative_speed": float(g), "collisions": state["events"],
                            "pair": (i, j), "cluster_mass": float(total(m[k] for k in members))}
                break
        state["events"] += 1
        event_times.append(float(t))
        if r == zero or (g < delta and subthreshold == "sticky"):
            kinds["merge"] += 1
            merged = ((m1 * v[i] + m2 * v[j]) / (m1 + m2), m1 + m2)
            if j == 0:      # across the seam: the merged cluster takes the front of the list
                v[0], m[0] = merged
                del v[i], m[i], gap[i]
            else:           # the merged cluster keeps the right member's gap
                (v[i], m[i]), gap[i] = merged, gap[j]
                del v[j], m[j], gap[j]
        else:
            rr = r if g >= delta else one
            kinds["inelastic" if g >= delta else "elastic"] += 1
            if rr == one and m1 == m2:
                v[i], v[j] = v[j], v[i]                      # equal masses, elastic: exchange, exactly
            else:
                v[i], v[j] = (v[i] - (one + rr) * m2 / (m1 + m2) * g,
                              v[j] + (one + rr) * m1 / (m1 + m2) * g)
    time = [float(s) for s in samples]
    collisions_per_particle = [c / n for c in out["collisions"]]
    return Evolution(time=time, temperature=out["temperature"], kinetic_energy=out["kinetic_energy"],
                     clusters=out["clusters"], collisions=out["collisions"],
                     collisions_per_particle=collisions_per_particle, status=status, collapse=collapse,
                     event_times=event_times, event_kinds=kinds, particles=n, total_mass=float(total_mass))


# ------------------------------------------------------------------------------------------ command line
def log_grid(t_max, per_decade):
    """t = 0, then `per_decade` log-spaced times per decade from t = 1, and t_max (as shockgas-sim
    describes its default grid; its own rounding of the grid may differ in the last digit)."""
    times, k = [0.0], 0
    while per_decade > 0:
        t = 10.0 ** (k / per_decade)
        if t >= t_max * (1 - 1e-12):
            break
        times.append(t)
        k += 1
    times.append(float(t_max))
    return times


def read_initial_condition(path):
    """(position, velocity, mass or None, ring_length) from a shockgas-sim --init file."""
    import shockgas  # the project's one HDF5 reader
    position, velocity, mass, ring_length = shockgas.read_initial_condition(path)
    # Plain floats: the decimal arithmetic (--digits) converts each exactly.
    return ([float(u) for u in position], [float(u) for u in velocity],
            None if mass is None else [float(u) for u in mass], ring_length)


def main(argv=None):
    from shockgas.cli import ArgumentParser  # a user's mistake in one line, exit status 2

    parser = ArgumentParser(
        description="Plain event-driven reference for shockgas-sim (docs/reference-check.md): runs an "
                    "--init file and prints t, T, kinetic energy, clusters and collisions per particle.")
    parser.add_argument("init", help="initial condition FILE.h5 (the format of shockgas-sim --init)")
    parser.add_argument("-r", "--restitution", type=float, default=0.9, help="r in [0, 1] (default 0.9)")
    parser.add_argument("-d", "--threshold", type=float, default=0.01, help="velocity threshold delta (default 0.01)")
    parser.add_argument("--subthreshold", choices=("elastic", "sticky"), default="elastic")
    parser.add_argument("--collapse-speed", type=float, default=1e-12)
    parser.add_argument("-t", "--t-max", type=float, default=10.0)
    parser.add_argument("--samples-per-decade", type=int, default=10)
    parser.add_argument("--sample-times", default="", help="extra sample times, comma separated")
    parser.add_argument("--max-events", type=int, default=None, help="stop after this many events")
    parser.add_argument("--digits", type=int, default=None,
                        help="compute in decimal arithmetic with this many digits (e.g. 40) instead of doubles")
    parser.add_argument("--compare", metavar="RUN.h5",
                        help="a shockgas-sim output of this init file (-R 1): take its r, delta, mechanism, "
                             "collapse speed and sample times, and print its values beside the reference's")
    args = parser.parse_args(argv)
    extra = check_arguments(args)
    try:
        position, velocity, mass, ring_length = read_initial_condition(args.init)
    except FileNotFoundError as error:  # the shockgas module's message names the path
        raise UsageError(str(error)) from None
    except ValueError as error:  # read_initial_condition's own reason (a missing dataset, a bad value)
        raise UsageError("%s: %s" % (args.init, error)) from None
    except OSError as error:
        raise UsageError("%s: not a readable initial condition (%s)" % (args.init, error)) from None
    run = None
    if args.compare:
        import hashlib

        import shockgas
        try:
            run = shockgas.read_run(args.compare)
        except (OSError, shockgas.SchemaError) as error:
            raise UsageError(str(error)) from None
        # The run records the SHA-256 of the file it started from: a run of another start (or of no
        # init file at all) compared with this one would show differences that are no engine's fault.
        recorded = run.attrs.get("init_file_sha256", "")
        if not recorded:
            raise UsageError("%s was not made from an init file (no init_file_sha256): it cannot be compared with %s"
                             % (args.compare, args.init))
        with open(args.init, "rb") as handle:
            actual = hashlib.sha256(handle.read()).hexdigest()
        if actual != recorded:
            raise UsageError("%s is not the initial condition %s was run from (its SHA-256 %s differs from the run's "
                             "init_file_sha256 %s)" % (args.init, args.compare, actual[:12], recorded[:12]))
        if run.realizations != 1:
            raise UsageError("%s has %d realizations; a run of one init file has 1" % (args.compare, run.realizations))
        args.restitution, args.threshold = run.attrs["restitution"], run.attrs["velocity_threshold"]
        args.subthreshold, args.collapse_speed = run.attrs["subthreshold"], run.attrs["collapse_speed"]
        times = [float(u) for u in run.time]
    else:
        times = sorted(set(log_grid(args.t_max, args.samples_per_decade) + extra))
    try:
        result = simulate(position, velocity, mass, ring_length, args.restitution, args.threshold,
                          args.subthreshold, args.collapse_speed, times, args.max_events, args.digits)
    except ValueError as error:  # a start simulate refuses (unsorted, outside [0, L), ...), in one line
        raise UsageError("%s: %s" % (args.init, error)) from None
    print("# reference_gas: N = %d, L = %r, r = %r, delta = %r, %s sub-threshold collisions, %s; %s after %d "
          "events (%s)" % (len(position), ring_length, args.restitution, args.threshold, args.subthreshold,
                           "doubles" if args.digits is None else "%d digits" % args.digits, result.status,
                           len(result.event_times), ", ".join("%d %s" % (v, k) for k, v in result.event_kinds.items())))
    if result.collapse:
        print("# collapse at t = %.17g after %d collisions: relative speed %.3g, cluster mass %g" % (
            result.collapse["time"], result.collapse["collisions"], result.collapse["relative_speed"],
            result.collapse["cluster_mass"]))
        if run is not None and run.collapse is not None:
            print("# shockgas-sim: collapse at t = %.17g after %d collisions: relative speed %.3g, cluster mass %g" % (
                run.collapse["time"][0], run.collapse["collisions"][0], run.collapse["relative_speed"][0],
                run.collapse["cluster_mass"][0]))
    header = "%-22s %-24s %-24s %-8s %-14s" % ("t", "T", "kinetic_energy", "clusters", "collisions/N")
    if run is not None:
        header += "  | shockgas-sim: T, kinetic_energy, clusters, collisions/N"
    print(header)
    for k, t in enumerate(result.time):
        line = "%-22.17g %-24.17g %-24.17g %-8s %-14.10g" % (
            t, result.temperature[k], result.kinetic_energy[k], result.clusters[k], result.collisions_per_particle[k])
        if run is not None:
            line += "  | %.17g %.17g %s %.10g" % (run.temperature[0][k], run.kinetic_energy[0][k],
                                                 run.clusters[0][k], run.collisions_per_particle[0][k])
        print(line)
    return 0


class UsageError(Exception):
    """A user's mistake: one line "reference_gas.py: error: ..." on stderr, exit status 2."""


# The bounds shockgas-sim puts on --samples-per-decade (sim/model/src/parameters.cpp, validate).
SAMPLES_PER_DECADE_RANGE = (1, 1000)


def check_arguments(args):
    """Refuses (UsageError) a command-line value that simulate() would refuse with a traceback, or
    would run on to print rows that mean nothing (a negative --t-max, --max-events below 1), before
    any file is read; the rules are shockgas-sim's where it has the option (sim/model/src/parameters.cpp).
    Returns --sample-times as a list of floats."""
    if not 0.0 <= args.restitution <= 1.0:
        raise UsageError("-r/--restitution %r: the restitution coefficient r lies in [0, 1]" % args.restitution)
    if not (math.isfinite(args.threshold) and args.threshold >= 0.0):
        raise UsageError("-d/--threshold %r: the velocity threshold delta is finite and >= 0" % args.threshold)
    if not args.collapse_speed >= 0.0:
        raise UsageError("--collapse-speed %r: a speed >= 0" % args.collapse_speed)
    if args.threshold > 0.0 and args.collapse_speed > args.threshold:
        raise UsageError("--collapse-speed %r exceeds the threshold delta = %r: every inelastic collision is then "
                         "at least delta, and a collapse would be declared falsely (shockgas-sim refuses it too)"
                         % (args.collapse_speed, args.threshold))
    if not (math.isfinite(args.t_max) and args.t_max > 0.0):
        raise UsageError("-t/--t-max %r: the run starts at t = 0 and needs a finite t_max > 0" % args.t_max)
    low, high = SAMPLES_PER_DECADE_RANGE
    if not low <= args.samples_per_decade <= high:
        raise UsageError("--samples-per-decade %d: between %d and %d (as shockgas-sim)" % (args.samples_per_decade,
                                                                                           low, high))
    if args.max_events is not None and args.max_events < 1:
        raise UsageError("--max-events %d: at least 1 (leave it out for no limit)" % args.max_events)
    if args.digits is not None and not 1 <= args.digits <= decimal.MAX_PREC:
        raise UsageError("--digits %d: decimal arithmetic needs 1 significant digit or more (40 is the test's), "
                         "at most %d" % (args.digits, decimal.MAX_PREC))
    extra = []
    for text in args.sample_times.split(","):
        if not text.strip():
            continue
        try:
            t = float(text)
        except ValueError:
            raise UsageError("--sample-times: %r is not a number (times are comma separated, such as 0.5,2.5)"
                             % text.strip()) from None
        if not (math.isfinite(t) and 0.0 <= t <= args.t_max):
            raise UsageError("--sample-times: %s lies outside [0, t_max = %r]" % (text.strip(), args.t_max))
        extra.append(t)
    return extra


if __name__ == "__main__":
    # Every init file is HDF5, read through the shockgas module (numpy and h5py), whose cli also says a
    # user's mistake in one line: a python3 without them is told so here, before anything, in one line.
    try:
        import h5py  # noqa: F401  (the shockgas module's; imported here to be named when missing)
        import numpy  # noqa: F401
    except ImportError as error:
        print("reference_gas.py: error: %s is missing (reading HDF5 needs numpy and h5py): run it with Debian's "
              "/usr/bin/python3 (python3-numpy, python3-h5py)" % (error.name or error), file=sys.stderr)
        sys.exit(2)
    # The module itself not beside this script (an installed copy in share/shockgas/python, the module
    # installed at another prefix), or one that does not import: said as such, not as numpy or h5py.
    try:
        import shockgas.cli
    except ImportError as error:
        if error.name == "shockgas":
            why = ("the Python module shockgas is missing (not beside this script, nor on Python's path): set "
                   "PYTHONPATH to the folder `cmake --install` put it in (such as <prefix>/lib/python%d.%d/"
                   "site-packages; docs/python.md), or run the source tree's python/reference_gas.py"
                   % sys.version_info[:2])
        else:
            why = "the Python module shockgas does not import (%s): another version of it on Python's path?" % error
        print("reference_gas.py: error: %s" % why, file=sys.stderr)
        sys.exit(2)
    try:
        sys.exit(main())
    except UsageError as error:
        shockgas.cli.fail(error)
