// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-plan's work (plan_command.hpp): the cheapest measured (delta,
// mechanism) that keeps an observable within a tolerance of the sticky gas to
// t_max, and what it costs. Every answer is a run of the map: no r, N, t or
// delta outside what it measured is extrapolated to.
#include "shockgas/analysis/plan_command.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "shockgas/model/parameters.hpp"

namespace shockgas::analysis {

namespace {

const std::vector<std::string> tolerances = {"3sigma", "1percent", "5percent"};
constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

std::string number(double value) {
    if (std::isnan(value)) return "n/a";
    return fmt::format("{:.3g}", value);
}

// t* of an option in words: a time, "> t_end" for a run whose observable had not
// left by its end, "never" for one that was never within the tolerance.
std::string departure_words(double departure_time, double t_end) {
    if (std::isnan(departure_time)) return "never within";
    if (std::isinf(departure_time)) return fmt::format("> {:g}", t_end);
    return fmt::format("{:.3g}", departure_time);
}

std::string list_numbers(const std::vector<double>& values) {
    std::vector<std::string> words;
    for (double value : values) words.push_back(fmt::format("{:g}", value));
    return fmt::format("{}", fmt::join(words, ", "));
}

// The runs of the map at r, in the map's order.
std::vector<const ValidityRun*> runs_at(const ValidityMap& map, double restitution) {
    std::vector<const ValidityRun*> found;
    for (const auto& run : map.runs)
        if (same_restitution(run.restitution, restitution)) found.push_back(&run);
    return found;
}

void check_request(const ValidityMap& map, const PlanRequest& request) {
    if (!(request.t_max > 0.0) || !std::isfinite(request.t_max))
        throw InputError(fmt::format("--t-max must be positive and finite, not {:g}", request.t_max));
    if (request.particles < 2)
        throw InputError(fmt::format("--particles must be at least 2, not {}", request.particles));
    if (std::find(tolerances.begin(), tolerances.end(), request.tolerance) == tolerances.end())
        throw InputError(fmt::format("--tolerance must be one of {}, not '{}'", fmt::join(tolerances, ", "),
                                     request.tolerance));
    if (std::find(map.observables.begin(), map.observables.end(), request.observable) == map.observables.end())
        throw InputError(fmt::format("unknown observable '{}': the map measured {}", request.observable,
                                     fmt::join(map.observables, ", ")));
    std::set<std::string> criteria;
    for (const auto& run : map.runs)
        for (const auto& departure : run.departures)
            if (departure.observable == request.observable) criteria.insert(departure.criterion);
    if (criteria.count(request.tolerance) == 0) {
        std::vector<std::string> measured;
        for (const auto& tolerance : tolerances)
            if (criteria.count(tolerance) != 0) measured.push_back(tolerance);
        throw InputError(fmt::format("the map has not measured {} by {}: {}", request.observable, request.tolerance,
                                     measured.empty() ? std::string("it has no departure of it")
                                                      : fmt::format("it measured it by {} only",
                                                                    fmt::join(measured, ", "))));
    }
}

PlanOption judge(const ValidityRun& run, const PlanRequest& request) {
    PlanOption option;
    option.run = run.name;
    option.velocity_threshold = run.velocity_threshold;
    option.subthreshold = run.subthreshold;
    option.particles = run.particles;
    option.t_end = run.t_end;
    const ValidityDeparture* departure = find_departure(run, request.observable, request.tolerance);
    option.measured = departure != nullptr;
    option.departure_time = departure != nullptr ? departure->departure_time : not_a_number;
    if (!option.measured)
        option.why_not = fmt::format("not measured by {}", request.tolerance);
    else if (request.t_max > run.t_end)
        option.why_not = fmt::format("measured to t = {:g} only", run.t_end);
    else if (std::isnan(option.departure_time))
        option.why_not = "never within it";
    else if (!(option.departure_time > request.t_max))
        option.why_not = "leaves before t_max";
    option.valid = option.why_not.empty();
    // The cost model (docs/validity.md): CPU time is proportional to collisions,
    // so the run's CPU seconds per particle-collision scale to the user's N and
    // to the collisions per particle the run had made by t_max.
    option.collisions_per_particle = collisions_per_particle_at(run, request.t_max);
    const double at_end = collisions_per_particle_at(run, run.t_end);
    const double per_particle_collision =
        run.cpu_seconds / (static_cast<double>(run.realizations) * static_cast<double>(run.particles) * at_end);
    option.cpu_seconds_per_realization = at_end > 0.0 && std::isfinite(per_particle_collision)
                                             ? per_particle_collision * static_cast<double>(request.particles) *
                                                   option.collisions_per_particle
                                             : not_a_number;
    return option;
}

// Fewer collisions per particle by t_max first (an unmeasurable cost last); among
// equal costs the larger delta (the coarser approximation costs no more), then
// the mechanism by name, so that the answer never depends on the map's order.
bool cheaper(const PlanOption& a, const PlanOption& b) {
    const bool a_known = !std::isnan(a.collisions_per_particle), b_known = !std::isnan(b.collisions_per_particle);
    if (a_known != b_known) return a_known;
    if (a_known && a.collisions_per_particle != b.collisions_per_particle)
        return a.collisions_per_particle < b.collisions_per_particle;
    if (a.velocity_threshold != b.velocity_threshold) return a.velocity_threshold > b.velocity_threshold;
    return a.subthreshold < b.subthreshold;
}

}  // namespace

Plan make_plan(const ValidityMap& map, const PlanRequest& request) {
    check_request(map, request);
    const auto at_r = runs_at(map, request.restitution);
    if (at_r.empty()) {
        std::set<double> measured;
        for (const auto& run : map.runs) measured.insert(run.restitution);
        throw InputError(fmt::format("r = {:g} is not among the map's restitutions: it measured r = {} (give one "
                                     "of them; the map does not interpolate in r)",
                                     request.restitution,
                                     list_numbers(std::vector<double>(measured.begin(), measured.end()))));
    }
    std::int64_t smallest_ring = at_r.front()->particles;
    for (const auto* run : at_r) smallest_ring = std::min(smallest_ring, run->particles);
    if (request.particles < smallest_ring)
        throw InputError(fmt::format("N = {} is below the map's rings at r = {:g}: smaller rings reach their "
                                     "finite-size regime sooner, so the map, measured at N = {}, says nothing of "
                                     "them; give N >= {}",
                                     request.particles, request.restitution, smallest_ring, smallest_ring));
    // A run stands for rings at least its own size: a larger ring reaches its
    // finite-size regime later, so what held in the run holds there.
    std::vector<const ValidityRun*> candidates;
    for (const auto* run : at_r)
        if (run->particles <= request.particles) candidates.push_back(run);
    double reach = 0.0, first_sample = std::numeric_limits<double>::infinity();
    for (const auto* run : candidates) {
        reach = std::max(reach, run->t_end);
        if (!run->time.empty()) first_sample = std::min(first_sample, run->time.front());
    }
    if (request.t_max > reach)
        throw InputError(fmt::format("t_max = {:g} lies beyond the measured map, which reaches t = {:g} at r = {:g}",
                                     request.t_max, reach, request.restitution));
    if (request.t_max < first_sample)
        throw InputError(fmt::format("t_max = {:g} lies before the map's first sample time, t = {:g}, at r = {:g}: "
                                     "its cost there is not measured",
                                     request.t_max, first_sample, request.restitution));

    Plan plan;
    plan.map_version = map.version;
    for (const auto* run : candidates) plan.options.push_back(judge(*run, request));
    std::stable_sort(plan.options.begin(), plan.options.end(), [](const PlanOption& a, const PlanOption& b) {
        if (a.velocity_threshold != b.velocity_threshold) return a.velocity_threshold > b.velocity_threshold;
        if (a.subthreshold != b.subthreshold) return a.subthreshold < b.subthreshold;
        return a.particles > b.particles;
    });
    std::size_t best = plan.options.size();
    for (std::size_t i = 0; i < plan.options.size(); ++i)
        if (plan.options[i].valid && (best == plan.options.size() || cheaper(plan.options[i], plan.options[best])))
            best = i;
    if (best == plan.options.size()) {
        // The nearest miss: the smallest measured delta (the closest to the
        // sticky gas), and of its mechanisms the one that stays longest.
        const PlanOption* nearest = nullptr;
        for (const auto& option : plan.options) {
            if (!option.measured) continue;
            const auto later = [](double a, double b) { return std::isnan(b) || (!std::isnan(a) && a > b); };
            if (nearest == nullptr || option.velocity_threshold < nearest->velocity_threshold ||
                (option.velocity_threshold == nearest->velocity_threshold &&
                 later(option.departure_time, nearest->departure_time)))
                nearest = &option;
        }
        std::string miss;
        if (nearest != nullptr) {
            const std::string which = fmt::format("the smallest measured delta, {:g} ({})",
                                                  nearest->velocity_threshold, nearest->subthreshold);
            if (std::isnan(nearest->departure_time))
                miss = fmt::format("; {}, is never within it", which);
            else if (std::isinf(nearest->departure_time))
                miss = fmt::format("; {}, had not left by the end of its run, t = {:g}", which, nearest->t_end);
            else
                miss = fmt::format("; {}, leaves at t* = {:.3g}", which, nearest->departure_time);
        }
        throw InputError(fmt::format("no measured delta keeps {} within {} to t = {:g} at r = {:g}{}",
                                     request.observable, request.tolerance, request.t_max, request.restitution,
                                     miss));
    }
    plan.best = best;
    return plan;
}

std::string format_plan(const Plan& plan, const PlanRequest& request) {
    const PlanOption& best = plan.options[plan.best];
    std::string text = fmt::format(
        "cheapest: delta = {:g}, sub-threshold {}: {} stays within {} of the sticky gas to t = {:g} at r = {:g} "
        "(it leaves at t* {}{}; measured at N = {} to t = {:g})\n",
        best.velocity_threshold, best.subthreshold, request.observable, request.tolerance, request.t_max,
        request.restitution, std::isinf(best.departure_time) ? "" : "= ",
        departure_words(best.departure_time, best.t_end), best.particles, best.t_end);
    text += fmt::format("cost at N = {}: {} collisions per particle by t = {:g}, about {} s of CPU per realization\n",
                        request.particles, number(best.collisions_per_particle), request.t_max,
                        number(best.cpu_seconds_per_realization));
    text += fmt::format("every measured (delta, mechanism) at r = {:g}: t* of {} by {}, cost to t = {:g} at N = {}\n",
                        request.restitution, request.observable, request.tolerance, request.t_max, request.particles);
    text += fmt::format("  {:>10} {:>9} {:>10} {:>12} {:>14} {:>16}  {}\n", "delta", "mechanism", "map N", "t*",
                        "coll/particle", "CPU s/realization", "verdict");
    for (std::size_t i = 0; i < plan.options.size(); ++i) {
        const PlanOption& option = plan.options[i];
        const std::string verdict = i == plan.best ? "cheapest" : option.valid ? "valid" : option.why_not;
        text += fmt::format("  {:>10g} {:>9} {:>10} {:>12} {:>14} {:>16}  {}\n", option.velocity_threshold,
                            option.subthreshold, option.particles, departure_words(option.departure_time, option.t_end),
                            number(option.collisions_per_particle), number(option.cpu_seconds_per_realization),
                            verdict);
    }
    text += fmt::format("map: {} ('{}')\n", plan.map_version, request.map_file);
    return text;
}

void run_plan(const PlanRequest& request, std::FILE* out) {
    if (request.map_file.empty())
        throw InputError("no validity map: this build has made none (make it with `cmake --build --preset quick "
                         "--target fig_validity`), or give one with --map FILE");
    const ValidityMap map = read_validity_map(request.map_file);
    const Plan plan = make_plan(map, request);
    fmt::print(out, "{}", format_plan(plan, request));
}

}  // namespace shockgas::analysis
