#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Cost and accuracy of every figure at one fidelity, as Markdown tables.

Usage: /usr/bin/python3 tools/fidelity_report.py BUILD_DIR [quick|paper] [--readme | --check-readme README.md | --progress]

Reads the runs (build/paper_targets/<fidelity>/<fig>/*.h5 written by shockgas-sim:
particles, realizations, cpu_seconds, peak_memory_bytes, total_collisions) and the
analysis results next to them (decay exponents, crossover and scaling fits,
shocks, the speed/accuracy comparison), and prints what the README's results and
cost tables and docs/figures-and-fidelity.md show. Reads only; computes nothing but sums and ratios.

--readme prints instead the rows of the README's results table (| claim | quick tier | paper tier |
paper / theory |) whose numbers this build measured, ready to paste, so the README's numbers come from
a build rather than from memory: the claim, this tier's cell and the paper / theory cell from the
build's files, the other tier's cell as the README.md of this source tree (beside tools/) has it in the
row of the same claim ("—" where it has none).

--check-readme README.md exits 1, naming each row, unless for every one of those rows README.md has a
table row of the same claim whose cell of this tier and paper / theory cell are the build's: the test
that keeps the README's numbers from going stale (ctest figures.readme_numbers, after the figures are
built; the simulations are deterministic, so a build at the same commit measures the same numbers on
any computer). The other tier's cell is not checked: a quick build cannot measure it.

--progress prints instead where a build that is still running stands (a paper build can take days): for
every run of every figure's parameter file (paper_targets/<figure>.<fidelity>.json), the parts and
realizations done, the CPU seconds spent (the finished files' and the running checkpoints'
cpu_seconds), the realization in progress and how far it got, and, once a part of a run has
finished, the CPU seconds its remaining parts would take at the mean of its finished ones (marked as
an extrapolation): each part not begun at that mean, each running part at that mean less the CPU
seconds its checkpoint has already spent (counted under "so far"; none below zero). fig_tail, which
runs the far-tail sampler shockgas-tail and has no parameter file (paper_targets/fig_tail.cmake), has
a row of its own: done with its tail.h5 (and that file's cpu_seconds), else the sampler's last
progress line in BUILD_DIR/paper-tier.log (the sampler keeps no checkpoint: its CPU is counted once
tail.h5 is written). Checkpoints a run moved aside because they were written by another code version
(<output>.checkpoint.from-<version>, docs/checkpoints-and-mpi.md) are not counted in the table: they
are listed under it as set aside, each with its CPU seconds and realizations, since only the old
program can finish them. Safe to run beside the build: it only reads.

Refused with one line "fidelity_report.py: error: ..." on stderr and exit status 2, rather than
tables that are empty: a BUILD_DIR that does not exist or has no paper_targets/, a fidelity other
than quick or paper or one the build has no paper_targets/<fidelity>/ for (a quick build asked for
paper), no results in it yet (except --progress, whose point is a build under way), --check-readme
without a file or with one that does not exist, and unknown options. -h or --help prints this help
(exit 0), wherever it stands, even where numpy and h5py are missing.
"""
import glob
import math
import os
import re
import signal
import sys

# Piped into head, the report stops quietly when head has read enough, as a shell tool does
# (Python would otherwise raise BrokenPipeError with a traceback).
signal.signal(signal.SIGPIPE, signal.SIG_DFL)

USAGE = "usage: fidelity_report.py [-h] BUILD_DIR [quick|paper] [--readme | --check-readme README.md | --progress]"


def stick_expectation(scaling_in_eps):
    """The paper/theory cell of the t_stick exponent: -3/2 as eps -> 0, and, where the results file has it
    (files of an older shockgas-analyze do not), what the same rule reads on an exact eps^(-3/2) crossover
    at the run's eps (Haff's finite-eps terms tilt it)."""
    reference = scaling_in_eps.get("t_stick_reference_exponent")
    if reference is None or reference != reference:
        return "−3/2"
    return f"−3/2 as ε → 0; {reference:.3f} read by the same rule on an exact ε^(−3/2) crossover at these ε"


def print_help():
    """--help: the usage line, this docstring (less its own usage line) and the arguments, as argparse
    would print them; the words are parsed by hand below (their refusals are this script's own)."""
    text = "\n".join(line for line in __doc__.strip("\n").splitlines() if not line.startswith("Usage:"))
    text = text.replace("\n\n\n", "\n\n")  # the blank lines around that usage line: one
    print(f"{USAGE}\n\n{text}\n")
    print("positional arguments:\n"
          "  BUILD_DIR             the build tree (default: build)\n"
          "  quick|paper           the fidelity (default: quick)\n\n"
          "options:\n"
          "  -h, --help            show this help message and exit\n"
          "  --readme              print the README's results rows this build measured\n"
          "  --check-readme README.md\n"
          "                        exit 1 unless README.md holds every one of those numbers\n"
          "  --progress            where a build still running stands")


if "-h" in sys.argv[1:] or "--help" in sys.argv[1:]:  # before the imports: help needs neither numpy nor h5py
    print_help()
    sys.exit(0)

import shockgas_path  # noqa: E402  (python/ of this source tree on Python's path: tools/shockgas_path.py)

# numpy, h5py or the module missing: one line naming it, exit status 2.
shockgas_path.require("fidelity_report.py")
import shockgas  # noqa: E402
# A user's mistake: one line on stderr, exit 2 (exit 1 is --check-readme's stale rows).
from shockgas.cli import fail  # noqa: E402

check_readme = None
argv = sys.argv[1:]
if argv.count("--check-readme") > 1:
    fail("--check-readme given twice")
if "--check-readme" in argv:
    position = argv.index("--check-readme")
    if position + 1 >= len(argv) or argv[position + 1].startswith("-"):
        fail("--check-readme needs the README to check: --check-readme README.md")
    check_readme = argv[position + 1]
    del argv[position:position + 2]
readme = "--readme" in argv
progress = "--progress" in argv
arguments = [a for a in argv if a not in ("--readme", "--progress")]
if len(arguments) > 2 or any(a.startswith("-") for a in arguments):
    fail(f"{' '.join(a for a in arguments if a.startswith('-')) or 'too many arguments'}: {USAGE}")
if readme + progress + (check_readme is not None) > 1:
    fail(f"--readme, --check-readme and --progress are alternatives: {USAGE}")
build = arguments[0] if len(arguments) > 0 else "build"
fidelity = arguments[1] if len(arguments) > 1 else "quick"
base = os.path.join(build, "paper_targets", fidelity)
# A wrong directory or fidelity would otherwise print empty tables and exit 0.
if fidelity not in ("quick", "paper"):
    fail(f"the fidelity is quick or paper, not '{fidelity}'")
if not os.path.isdir(build):
    fail(f"'{build}': no such directory")
if not os.path.isdir(os.path.join(build, "paper_targets")):
    fail(f"'{build}' is not a configured build tree (no paper_targets/ in it)")
if not os.path.isdir(base):
    fail(f"'{build}' has no {fidelity}-fidelity pipeline (no paper_targets/{fidelity}/ in it): configure it with "
         f"-DSHOCKGAS_FIDELITY={fidelity}, or name the fidelity it was built at")
if check_readme is not None and not os.path.isfile(check_readme):
    fail(f"{check_readme}: no such file")
if not progress and not glob.glob(os.path.join(glob.escape(base), "*", "*.h5")):
    fail(f"no results in {base}: build the figures first (cmake --build {build} --target figures)")


def attrs(path, group):
    return shockgas.read_results(path)[group].attrs


def why_missing(attributes, name, fallback):
    """The reason shockgas-analyze stored for a number it could not measure (the attribute `name`: a
    `<number>_note`, `<number>_sigma_note` or `tail_error`), or `fallback` for a file that has none."""
    reason = attributes.get(name)
    return reason if isinstance(reason, str) and reason else fallback


def window(decay):
    """The window systematic, or n/a where the analysis could not measure it (stored as NaN with a
    note: fewer than two one-decade windows inside the fit window)."""
    value = decay["exponent_window_systematic"]
    return "n/a" if value != value else f"{value:.3f}"


def power(x):
    """10⁵ for 1e5, 2·10⁴ for 2e4, 1.2·10⁴ for 1.2e4 (the README's way of writing sizes and times); 1643 as
    it is."""
    superscript = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")
    for digits in (0, 1):
        mantissa, exponent = f"{float(x):.{digits}e}".split("e")
        if float(f"{mantissa}e{exponent}") == float(x):
            break
    if float(f"{mantissa}e{exponent}") != float(x) or abs(int(exponent)) < 3:
        return f"{float(x):.4g}"
    tail = "10" + str(int(exponent)).translate(superscript)
    return tail if mantissa == "1" else f"{mantissa}·{tail}"


def sizes(attributes, decay):
    """N, realizations and fit window of a decay fit, as the README's cells give them."""
    return (f"N = {power(attributes['particles'])}, {attributes['realizations']} real., "
            f"t ∈ [{power(decay['t_lo'])}, {power(decay['t_hi'])}]")


def readme_rows():
    """(claim, this tier's cell, paper / theory cell) of each README results row this build measured,
    in the README's order."""
    rows = []
    for run, paper in [("r0", "0.67 / 2/3"), ("r0.5", "0.67"), ("r0.9", "0.66")]:
        path = os.path.join(base, "fig1", run + ".decay.h5")
        if not os.path.exists(path):
            continue
        results = shockgas.read_results(path)
        d, a = results["decay"].attrs, results.inputs()[0]
        rows.append((f"P1: T ~ t^−α, r = {a['restitution']:g}",
                     f"α = {d['exponent']:.3f} ± {d['exponent_sigma']:.3f} ± {window(d)} ({sizes(a, d)})", paper))
    path = os.path.join(base, "fig_crossovers", "crossovers.h5")
    if os.path.exists(path):
        d = attrs(path, "scaling_in_eps")
        rows.append(("P2/P3: t_stick ∝ ε^x", f"x = {d['t_stick_exponent']:.3f} ± {d['t_stick_exponent_sigma']:.3f}",
                     stick_expectation(d)))
        rows.append(("P3: T(t_stick) ∝ ε^x", f"x = {d['temperature_at_stick_exponent']:.3f} ± "
                     f"{d['temperature_at_stick_exponent_sigma']:.3f}", "+1"))
    # Fig. 4, then the same with sticky sub-threshold collisions (fig4_sticky, P5's other mechanism).
    for figure, ids, variant in [("fig4", ("P7", "P7/P8"), ""), ("fig4_sticky", ("P5/P7", "P5/P8"), ", sticky below δ")]:
        path = os.path.join(base, figure, "scaling.h5")
        if not os.path.exists(path):
            continue
        results = shockgas.read_results(path)
        d = results["collapse"].attrs
        histograms = [results[g].attrs for g in results.sections if g.startswith("histogram")]
        rows.append((f"{ids[0]}: P(v,t) = t^(1/3) Φ(v t^(1/3)){variant}, best β",
                     f"β = {d['beta']:.3f} ± {d['beta_sigma']:.3f} ({len(histograms)} histograms)", "1/3"))
        if histograms:
            kurtosis = [h["kurtosis"] for h in histograms]
            rows.append((f"{ids[1]}: kurtosis of Φ{variant}",
                         f"{min(kurtosis):.2f} … {max(kurtosis):.2f} ({len(histograms)} histograms)", "3.041 (exact)"))
    path = os.path.join(base, "fig5", "shocks.h5")
    if os.path.exists(path):
        results = shockgas.read_results(path)
        d, a = results["shocks0"].attrs, results.inputs()[0]
        rows.append((f"P9: shocks at t = {power(d['time'])} (N = {power(a['particles'])}, r = {a['restitution']:g}, "
                     f"δ = {power(a['velocity_threshold'])})", f"{d['shock_count']:.0f}",
                     f"N t^(−2/3) ≈ {d['expected_shock_count']:.0f}"))
        # The paper's reference line is the raw slope 1/t; the density-corrected one is this project's
        # (Eq. (7) for particles that stream in one stream: analysis/README.md), so both are shown.
        rows.append(("P9: tooth slope × t (Eq. 7), density-corrected; raw",
                     f"{d['density_corrected_slope_times_t']:.2f} ± {d['density_corrected_slope_times_t_sigma']:.2f}; "
                     f"raw {d['slope_times_t']:.2f} ± {d['slope_times_t_sigma']:.2f}", "1"))
    rows.extend(validity_rows())
    rows.extend(spheres_rows())
    rows.extend(dimension_rows())
    return rows


VALIDITY_CLAIMS = [  # (r, observable, criterion, what the claim names it)
    (0.9, "temperature", "3sigma", "T, 3σ"), (0.9, "temperature", "1percent", "T, 1 %"),
    (0.5, "temperature", "1percent", "T, 1 %"), (0.5, "structure_function", "5percent", "S(k t^(2/3) = 100), 5 %")]


def spheres_rows():
    """fig_spheres: the largest deviation from Haff's law up to t0 of each run, and the 2D r = 0.9 gas's
    clustering index at its last snapshot."""
    path = os.path.join(base, "fig_spheres", "cooling.h5")
    if not os.path.exists(path):
        return []
    f = shockgas.read_results(path)
    runs = {(int(g.attrs["dimension"]), float(g.attrs["restitution"])): g.attrs
            for name, g in f.groups.items() if name.startswith("input")}
    def deviation(d, r):
        return f"{100 * runs[(d, r)]['largest_haff_deviation']:.2g} %"
    clustered = runs[(2, 0.9)]
    cell = (f"{deviation(2, 0.9)}, {deviation(2, 0.99)} (2D, r = 0.9, 0.99); {deviation(3, 0.9)}, "
            f"{deviation(3, 0.99)} (3D); clustering index of 2D r = 0.9 at its end: "
            f"{clustered['final_clustering_index']:.1f} ± {clustered['final_clustering_index_sigma']:.1f}")
    return [("Beyond the ring: disks and spheres cool by Haff's law, max \\|T/T_Haff − 1\\| for t ≤ t₀ "
             "(φ = 0.1, δ = 10⁻²)", cell, "Haff, t₀ from Enskog")]


def dimension_rows():
    """fig_2d and fig_3d: the late exponent theta of each run (n/a where the run leaves no window between
    the predicted crossover and the finite-size time) and the plateau of its local exponent, and the
    crossover time's exponent against eps."""
    rows = []
    for d in (2, 3):
        path = os.path.join(base, f"fig_{d}d", "late.h5")
        if not os.path.exists(path):
            continue
        f = shockgas.read_results(path)
        runs = [g.attrs for name, g in sorted(f.groups.items()) if name.startswith("late_decay")]
        first = runs[0]
        def theta(a):
            fitted = "n/a" if a["theta"] != a["theta"] else \
                f"{a['theta']:.2f} ± {a['theta_sigma']:.2f} ± {a['theta_window_sigma']:.2f}"
            plateau = "n/a" if a["theta_plateau"] != a["theta_plateau"] else \
                f"{a['theta_plateau']:.2f} ± {a['theta_plateau_sigma']:.2f}"
            return f"ε = {a['eps']:g}: {fitted}, plateau {plateau}"
        cell = "; ".join(theta(a) for a in runs) + (f" (N = {power(first['particles'])}, φ = {first['packing_fraction']:g}, "
                                                    f"δ = {power(first['velocity_threshold'])})")
        burgers, aggregation = d / 2, 2 * d / (d + 2)
        rows.append((f"Beyond the ring, {d}D: late decay T ~ t^(−θ), θ ± jackknife ± window; plateau of the local "
                     "exponent ± jackknife", cell,
                     f"Burgers d/2 = {burgers:g}; aggregation 2d/(d+2) = {aggregation:g}"))
        crossover = f[f"crossover_d{d}"].attrs
        if crossover["crossover_exponent"] == crossover["crossover_exponent"]:
            rows.append((f"Beyond the ring, {d}D: crossover τ_c ~ ε^x (collision times)",
                         f"x = {crossover['crossover_exponent']:.2f} ± {crossover['crossover_exponent_sigma']:.2f} "
                         f"({crossover['crossover_points']} ε)", f"x = {crossover['predicted_exponent']:g}"))
        rows.extend(cluster_rows(d))
    return rows


def cluster_rows(d):
    """fig_2d_clusters or fig_3d_clusters (d = 2, 3): the largest cluster at the last snapshot of each run
    against N_c's scale eps^(-2d/(4-d)) (eps^-2 in 2D, eps^-6 in 3D)."""
    path = os.path.join(base, f"fig_{d}d_clusters", "clusters.h5")
    if not os.path.exists(path):
        return []
    f = shockgas.read_results(path)
    cells, scales, fractions = [], [], []
    for name, g in sorted(f.groups.items()):
        if not name.startswith("clusters"):
            continue
        last = list(g["snapshots"].groups.values())[-1].attrs
        eps = (1 - g.attrs["restitution"]) / 2
        cells.append(f"ε = {eps:g}: {last['largest_mass']:.0f} ± {last['largest_mass_sigma']:.0f}")
        scales.append(f"{g.attrs['critical_size_scale']:.0f}")
        fractions.append(100 * last["clustered_fraction"])
    exponent = "⁻²" if d == 2 else "⁻⁶"
    return [(f"Beyond the ring, {d}D: largest cluster at the end (particles, cells at twice the mean density)",
             "; ".join(cells) + f" (t = {power(last['time'])}; {min(fractions):.0f}–{max(fractions):.0f} % of the "
             "particles in clusters)", f"N_c ~ ε{exponent} = " + ", ".join(scales))]


def validity_rows():
    """fig_validity: t* ∝ δ^(−μ) of T and of the structure function (elastic below δ), and the observables
    that never joined the sticky gas in any run."""
    path = os.path.join(base, "fig_validity", "validity.h5")
    if not os.path.exists(path):
        return []
    rows = []
    f = shockgas.read_results(path)
    fits = [g.attrs for g in f["validity_map/fits"].groups.values()]
    runs = list(f["validity_map/runs"].groups.values())
    sizes_of_runs = [int(g.attrs["particles"]) for g in runs]
    main_n = max(set(sizes_of_runs), key=sizes_of_runs.count)  # the map's N; the N check is one run
    reals = max(int(g.attrs["realizations"]) for g in runs)
    t_end = max(float(g.attrs["t_end"]) for g in runs)
    for r, observable, criterion, name in VALIDITY_CLAIMS:
        fit = next((x for x in fits if abs(x["restitution"] - r) < 1e-9 and x["subthreshold"] == "elastic"
                    and x["observable"] == observable and x["criterion"] == criterion), None)
        if fit is None:
            continue
        cell = (f"μ = {fit['mu']:.2f} ± {fit['mu_sigma']:.2f} ({fit['points']} δ; {fit['follows']})"
                if fit["mu"] == fit["mu"] else fit["follows"])
        rows.append((f"δ validity: t* ∝ δ^(−μ) of {name}, r = {r:g}, elastic below δ",
                     f"{cell}; N = {power(main_n)}, {reals} real., t ≤ {power(t_end)}",
                     "δ⁻³ (v ~ t^(−1/3) reaches δ); δ⁻¹ (Shinde, Das & Rajesh)"))
    never = []
    for observable in ["cluster_density", "small_gap_fraction", "fragmentation_rate"]:
        notes = [g[f"departures/{observable}/5percent"].attrs["departure_time"] for g in runs
                 if int(g.attrs["particles"]) == main_n and g.attrs["restitution"] > 0.85
                 and g.attrs["subthreshold"] == "elastic"]
        if notes and all(t != t for t in notes):
            never.append(observable.replace("_", " "))
    if never:
        rows.append(("δ validity: cluster structure, r = 0.9, elastic below δ",
                     f"{', '.join(never)}: never within 5 % of the sticky gas for any δ (t ≤ {power(t_end)})",
                     "sticky-gas-like for t ≪ δ⁻¹ (Shinde, Das & Rajesh)"))
    return rows


def cells(line):
    """The cells of a Markdown table row (an escaped \\| stays inside its cell), or None."""
    line = line.strip()
    if not (line.startswith("|") and line.endswith("|")):
        return None
    return [cell.strip() for cell in re.split(r"(?<!\\)\|", line[1:-1])]


def readme_table(path):
    """claim -> the cells of that claim's row in the results table of the README at `path` ({} if none)."""
    table = {}
    if path and os.path.isfile(path):
        with open(path, encoding="utf-8") as handle:
            for line in handle:
                row = cells(line)
                if row and len(row) == 4:
                    table.setdefault(row[0], row)
    return table


# The column of each tier in the README's results table: | claim | quick tier | paper tier | paper / theory |.
COLUMN = {"quick": 1, "paper": 2}
HEADER = "| claim | quick tier | paper tier | paper / theory |"


def full_row(claim, value, theory, known):
    """The README row of a claim with this tier's value, the other tier's cell as the README has it."""
    row = ["—", "—"]
    if claim in known:
        row = list(known[claim][1:3])
    row[COLUMN[fidelity] - 1] = value
    return f"| {claim} | {row[0]} | {row[1]} | {theory} |"


if check_readme is not None:
    rows = readme_rows()
    if not rows:
        fail(f"none of the README's results in {base} (fig1/r*.decay.h5, fig_crossovers/crossovers.h5, "
             f"fig4/scaling.h5, fig5/shocks.h5): build the figures first")
    known = readme_table(check_readme)
    stale = [(claim, value, theory) for claim, value, theory in rows
             if claim not in known or known[claim][COLUMN[fidelity]] != value or known[claim][3] != theory]
    for claim, value, theory in stale:
        print(f"{check_readme} lacks this row measured by {build} (paste it in place of the stale one):\n"
              f"{full_row(claim, value, theory, known)}")
    print(f"{len(rows) - len(stale)} of {len(rows)} measured rows stand in {check_readme}")
    sys.exit(1 if stale else 0)

if readme:
    known = readme_table(os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", "README.md"))
    print(f"<!-- {fidelity} fidelity, measured by the build in {build}: "
          f"/usr/bin/python3 tools/fidelity_report.py {build} {fidelity} --readme -->")
    print(HEADER)
    print("|---|---|---|---|")
    for claim, value, theory in readme_rows():
        print(full_row(claim, value, theory, known))
    sys.exit(0)


# The far-tail sampler's progress line in a log (shockgas-tail's, cli::steps_progress_printer in
# sim/cli/src/progress.cpp), and the comment make prints
# when fig_tail starts it (paper_targets/fig_tail.cmake).
TAIL_PROGRESS = "shockgas-tail: progress: "
TAIL_STARTED = "[fig_tail] far-tail sampler"


def tail_progress_line(log):
    """The sampler's last progress line in `log` (paper-tier's) after the last start of fig_tail's
    sampler, "" if it started without one yet, or None if the log does not show it started."""
    try:
        with open(log, "rb") as handle:
            handle.seek(0, os.SEEK_END)
            handle.seek(max(0, handle.tell() - (8 << 20)))  # the end of a log days long is enough
            lines = handle.read().decode("utf-8", "replace").splitlines()
    except OSError:
        return None
    starts = [i for i, line in enumerate(lines) if TAIL_STARTED in line]
    if not starts:
        return None
    found = [line for line in lines[starts[-1]:] if line.startswith(TAIL_PROGRESS)]
    return found[-1][len(TAIL_PROGRESS):].strip() if found else ""


def progress_report():
    """Where each run of a build in progress stands (--progress)."""
    import json
    import time

    sources = os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", "paper_targets")
    print(f"### {fidelity} build {build}: progress at {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}\n")
    print("| figure | run | parts done | realizations done | CPU s so far | running now | remaining CPU s "
          "(extrapolated) |")
    print("|---|---|---|---|---|---|---|")
    total_cpu = total_remaining = 0.0
    set_aside = []
    for parameters in sorted(glob.glob(os.path.join(sources, f"*.{fidelity}.json"))):
        figure = os.path.basename(parameters)[:-len(f".{fidelity}.json")]
        for run in json.load(open(parameters, encoding="utf-8"))["runs"]:
            name, parts = run["name"], int(run.get("parts", 1))
            realizations = int(run["options"].get("realizations", 1))
            folder = os.path.join(base, figure)
            merged = os.path.join(folder, name + ".h5")
            finished = [merged] if os.path.exists(merged) else sorted(
                glob.glob(os.path.join(folder, glob.escape(name) + ".part*.h5")))
            finished = [f for f in finished if not f.endswith(".running.h5")]
            finished_attrs = [shockgas.attributes(f) for f in finished]
            cpu_done = [a["cpu_seconds"] for a in finished_attrs]
            done = sum(int(a["realizations"]) for a in finished_attrs)
            parts_done = parts if os.path.exists(merged) else len(finished)
            cpu = sum(cpu_done)
            running, running_cpu = [], []
            prefix = os.path.join(folder, glob.escape(name))
            for checkpoint in sorted(glob.glob(prefix + ".running.h5.checkpoint") +
                                     glob.glob(prefix + ".part*.running.h5.checkpoint")):
                c = shockgas.read(checkpoint, expect=("checkpoint", "spheres_checkpoint"))
                if isinstance(c, shockgas.SpheresCheckpoint):  # only the realizations begun are recorded
                    status = [0 if finished else 4 for _, finished in c.progress.values()]
                    status += [4] * (realizations - len(status))
                    samples = [n for n, _ in c.progress.values()] + [0] * (realizations - len(c.progress))
                else:
                    status, samples = list(c.realization_status), list(c.samples_done)
                done_here = sum(1 for s in status if s in (0, 1))
                reached = [c.time[n - 1] for s, n in zip(status, samples) if s == 4 and n > 0]
                cpu += c.attrs["cpu_seconds"]
                running_cpu.append(c.attrs["cpu_seconds"])
                part = os.path.basename(checkpoint)[len(name):].split(".running")[0].lstrip(".") or name
                running.append(f"{part}: {done_here}/{len(status)} done" +
                               (f", one at t = {max(reached):.3g}" if reached else ""))
            # Moved aside by a run of another code version (.from-<version>) or of edited parameters
            # (.from-other-run): both generations under one name.
            aside = {path[:-len(".previous")] if path.endswith(".previous") else path
                     for path in glob.glob(prefix + ".running.h5.checkpoint.from-*") +
                     glob.glob(prefix + ".part*.running.h5.checkpoint.from-*")}
            for path in sorted(aside):
                set_aside.append(path)
            remaining = ""
            if parts_done < parts and cpu_done:
                # Parts not begun at the mean of the finished ones; a running part at that mean less the
                # CPU its checkpoint has spent (already under "so far"), not a whole part on top of it.
                mean = sum(cpu_done) / len(cpu_done)
                not_begun = max(parts - parts_done - len(running_cpu), 0)
                estimate = not_begun * mean + sum(max(mean - spent, 0.0) for spent in running_cpu)
                total_remaining += estimate
                remaining = f"{estimate:.0f}"
            total_cpu += cpu
            print(f"| {figure} | {name} | {parts_done}/{parts} | {done}/{realizations} | {cpu:.0f} | "
                  f"{'; '.join(running) or '—'} | {remaining or '—'} |")
    # fig_tail: the far-tail sampler (paper_targets/fig_tail.cmake), no parameter file, no parts, no checkpoint.
    if os.path.isfile(os.path.join(sources, "fig_tail.cmake")):
        tail = os.path.join(base, "fig_tail", "tail.h5")
        if os.path.exists(tail):
            a = shockgas.attributes(tail)
            total_cpu += a["cpu_seconds"]
            chains = f"{a['chains']} chains" if "chains" in a else "—"
            print(f"| fig_tail | tail (shockgas-tail) | 1/1 | {chains} | {a['cpu_seconds']:.0f} | — | — |")
        else:
            line = tail_progress_line(os.path.join(build, "paper-tier.log"))
            now = ("—" if line is None else
                   "sampler started, no progress line yet (paper-tier.log)" if not line else
                   f"sampler: {line} (last progress line in paper-tier.log; no checkpoint: a stop loses it)")
            print(f"| fig_tail | tail (shockgas-tail) | 0/1 | — | 0 | {now} | — |")
    print(f"| **all** | | | | **{total_cpu:.0f}** | | **{total_remaining:.0f}** (finished parts' mean for each part "
          f"not begun; for each running part, that mean less its CPU so far) |")
    # shockgas-sim names a checkpoint it moves aside NAME.from-<version tag> (another simulator) or
    # NAME.from-other-run (--set-aside-other-runs: the run's parameters were edited), with ".<k>" added
    # when that name is taken (sim/run/src/checkpoint.cpp keep_aside).
    other_runs = [path for path in set_aside if re.fullmatch(r"other-run(\.\d+)?", path.split(".from-", 1)[1])]
    other_versions = [path for path in set_aside if path not in other_runs]

    def describe(path):
        """(the path to show, realizations and CPU s of its newest readable generation, bytes on disk)."""
        readable = path if os.path.exists(path) else path + ".previous"
        size = sum(os.path.getsize(p) for p in (path, path + ".previous") if os.path.exists(p))
        try:
            c = shockgas.read_checkpoint(readable)
            status = list(c.realization_status)
            what = (f"{sum(1 for s in status if s in (0, 1))}/{len(status)} realizations done, "
                    f"{c.attrs['cpu_seconds']:.0f} CPU s")
        except (OSError, KeyError, ValueError) as error:
            what = f"not readable ({error})"
        return readable, what, size

    if other_versions:
        print("\nSet aside, not counted above: checkpoints of another code version, moved aside when a run of this "
              "one started anew (the old program finishes one with --checkpoint FILE --resume; "
              f"docs/checkpoints-and-mpi.md), under {base}:\n")
        for path in other_versions:
            readable, what, _ = describe(path)
            print(f"- {os.path.relpath(readable, base)} (version {path.split('.from-', 1)[1]}): {what}")
    if other_runs:
        total = 0
        print("\nSet aside, not counted above: checkpoints of runs whose parameters were edited since (moved aside "
              "by shockgas-sim --set-aside-other-runs when the build reran the run as it is now; "
              "docs/checkpoints-and-mpi.md). No build continues one as this run: remove them when no longer "
              f"wanted. Under {base}:\n")
        for path in other_runs:
            readable, what, size = describe(path)
            total += size
            files = " and ".join(os.path.relpath(p, base) for p in (path, path + ".previous") if os.path.exists(p))
            print(f"- {os.path.relpath(readable, base)} (another run's parameters): {what}; "
                  f"{size / 1e6:.1f} MB on disk ({files})")
        if len(other_runs) > 1:
            print(f"\n{total / 1e6:.1f} MB on disk in all.")


if progress:
    progress_report()
    sys.exit(0)


def runs(figure):
    for path in sorted(glob.glob(os.path.join(base, figure, "*.h5"))):
        if ".part" not in path and shockgas.kind_of(path) == "run":
            yield os.path.basename(path)[:-3], shockgas.attributes(path)


print(f"### Cost per figure ({fidelity} fidelity, {build})\n")
print("| figure | runs | N | realizations | collisions | CPU s | peak memory |")
print("|---|---|---|---|---|---|---|")
total_cpu = 0.0
# fig4_sticky reuses fig4's r = 0 run, which is counted under fig4 only (its file is in fig4's folder).
for figure in ["fig1", "fig2", "fig3", "fig4", "fig4_sticky", "fig5", "fig_collapse", "fig_crossovers", "fig_haff",
               "fig_tradeoff"]:
    items = list(runs(figure))
    if not items:
        continue
    cpu = sum(a["cpu_seconds"] for _, a in items)
    total_cpu += cpu
    collisions = sum(int(a["total_collisions"]) for _, a in items)
    sizes = sorted({int(a["particles"]) for _, a in items})
    reals = sorted({int(a["realizations"]) for _, a in items})
    memory = max(a.get("peak_memory_bytes", 0.0) for _, a in items)
    fmt_n = ", ".join(f"{n:.0e}".replace("e+0", "e") for n in sizes)
    print(f"| {figure} | {len(items)} | {fmt_n} | {', '.join(map(str, reals))} | {collisions:.3g} | "
          f"{cpu:.0f} | {memory / 2**20:.0f} MiB |")
print(f"| **all** | | | | | **{total_cpu:.0f}** | |\n")


print("### Fitted numbers\n")
print("| quantity | measured | paper / theory |")
print("|---|---|---|")
for run, paper in [("r0", "0.67 / 2/3"), ("r0.5", "0.67"), ("r0.9", "0.66"), ("r0.99", "—")]:
    path = os.path.join(base, "fig1", run + ".decay.h5")
    if os.path.exists(path):
        d = attrs(path, "decay")
        print(f"| Fig. 1 decay exponent, {run.replace('r', 'r = ')} (window [{d['t_lo']:.0f}, {d['t_hi']:.0f}]) | "
              f"{d['exponent']:.3f} ± {d['exponent_sigma']:.3f} (stat) ± {window(d)} (window) | {paper} |")
path = os.path.join(base, "fig_crossovers", "crossovers.h5")
if os.path.exists(path):
    d = attrs(path, "scaling_in_eps")
    for name, label, expected in [("t_dissip", "t_dissip vs ε", "−1 (leading order)"),
                                  ("t_stick", "t_stick vs ε", stick_expectation(d)),
                                  ("temperature_at_stick", "T(t_stick) vs ε", "+1")]:
        print(f"| {label} exponent | {d[name + '_exponent']:.3f} ± {d[name + '_exponent_sigma']:.3f} | {expected} |")
for figure, title in [("fig4", "Fig. 4"), ("fig4_sticky", "Fig. 4, sticky below δ,")]:
    path = os.path.join(base, figure, "scaling.h5")
    if not os.path.exists(path):
        continue
    d = attrs(path, "collapse")
    print(f"| {title} scaling exponent β | {d['beta']:.3f} ± {d['beta_sigma']:.3f} | 1/3 |")
    results = shockgas.read_results(path)
    for g in sorted(k for k in results.sections if k.startswith("histogram")):
        a = results[g].attrs
        line = f"| {title} {a['label']}: kurtosis"
        value = (f"{a['kurtosis']:.3f} ± {a['kurtosis_sigma']:.3f}" if not math.isnan(a["kurtosis_sigma"])
                 else f"{a['kurtosis']:.3f} ± n/a ({why_missing(a, 'kurtosis_sigma_note', 'one realization')})")
        # A short run's tail often has too few bins, or a fit or jackknife replica at the search
        # bound, or too few realizations to weigh the bins by (analysis/README.md, Tail): the reason is
        # the one shockgas-analyze scaling stored beside the NaN (tail_gamma_note, tail_gamma_sigma_note,
        # tail_error); files without them get the report's own words (why_missing).
        if "tail_gamma" in a:
            line += ", tail γ"
            if math.isnan(a["tail_gamma"]):
                value += f"; γ n/a ({why_missing(a, 'tail_gamma_note', 'at the search bound')})"
            elif math.isnan(a["tail_gamma_sigma"]):
                # The jackknife's σ is n/a; the fit's own Δχ² = 1 width, where measured, still bounds γ.
                reason = why_missing(a, "tail_gamma_sigma_note", "a replica at the search bound")
                fit_sigma = a.get("tail_gamma_fit_sigma", math.nan)
                value += (f"; γ = {a['tail_gamma']:.2f} ± {fit_sigma:.2f} (Δχ² = 1; jackknife n/a: {reason})"
                          if not math.isnan(fit_sigma) else f"; γ = {a['tail_gamma']:.2f} ± n/a ({reason})")
            else:
                value += f"; γ = {a['tail_gamma']:.2f} ± {a['tail_gamma_sigma']:.2f}"
        elif "tail_error" in a:
            line += ", tail γ"
            value += f"; γ n/a ({why_missing(a, 'tail_error', 'too few tail bins')})"
        print(f"{line} | {value} | 3.041 (exact Φ); γ = 3 asymptotically |")
path = os.path.join(base, "fig5", "shocks.h5")
if os.path.exists(path):
    d = attrs(path, "shocks0")
    print(f"| Fig. 5 shocks at t = {d['time']:g} | {d['shock_count']:.0f} | N t^(−2/3) = {d['expected_shock_count']:.1f} |")
    print(f"| Fig. 5 segment slope × t, density-corrected | {d['density_corrected_slope_times_t']:.2f} ± "
          f"{d['density_corrected_slope_times_t_sigma']:.2f} | 1 (Eq. 7) |")

path = os.path.join(base, "fig_tradeoff", "tradeoff.h5")
if os.path.exists(path):
    print("\n### Threshold and sub-threshold mechanism (r = 0.9; deviation from the reference run)\n")
    tradeoff = shockgas.read_results(path)
    a = tradeoff.inputs()[0]  # the reference run's attributes, copied forward
    coll = a["total_collisions"] / a["particles"] / a["realizations"]
    print(f"Reference: δ = {a['velocity_threshold']:g}, {a['subthreshold']}, N = {a['particles']}, "
          f"{a['realizations']} realizations, t = {a['t_max']:g}: {coll:.3g} collisions per particle, "
          f"{a['cpu_seconds']:.1f} CPU s.\n")
    print("| δ | sub-threshold | collisions/particle | CPU s | max \\|ΔT/T\\| | departs at t | δ^−3 |")
    print("|---|---|---|---|---|---|---|")
    for g in sorted((k for k in tradeoff.sections if k.startswith("compare")), key=lambda k: int(k[7:])):
        a = tradeoff[g].attrs
        print(f"| {a['velocity_threshold']:g} | {a['subthreshold']} | {a['collisions_per_particle']:.3g} | "
              f"{a['cpu_seconds']:.1f} | {a['max_abs_deviation']:.2g} | {a['departure_time']:g} | {a['t_valid']:.0e} |")
    print("\n### Statistical error of the sticky-gas exponent against CPU (r = 0, t ≤ 10⁴)\n")
    print("| N | realizations | CPU s | α ± σ |")
    print("|---|---|---|---|")
    for path in sorted(glob.glob(os.path.join(base, "fig_tradeoff", "stat_*.decay.h5")),
                       key=lambda p: (int(p.split("_N")[1].split("_")[0]), int(p.split("_R")[1].split(".")[0]))):
        results = shockgas.read_results(path)
        a, d = results.inputs()[0], results["decay"].attrs
        print(f"| {a['particles']:.0e} | {a['realizations']} | {a['cpu_seconds']:.2f} | "
              f"{d['exponent']:.4f} ± {d['exponent_sigma']:.4f} |")
