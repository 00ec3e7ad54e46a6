#include "shockgas/analysis/collapse.hpp"

#include <cmath>

#include "shockgas/h5.hpp"

namespace shockgas::analysis {

CollapseEvents collapse_events_from(const EnsembleResult& result, double restitution) {
    CollapseEvents events;
    events.inelasticity = (1.0 - restitution) / 2.0;  // r = 1 - 2 eps
    events.realizations = static_cast<std::size_t>(result.realizations);
    for (const auto& record : result.collapses) {
        events.time.push_back(record.report.time);
        events.cluster_mass.push_back(static_cast<double>(record.report.cluster_mass));
    }
    return events;
}

CollapseEvents read_collapse_events(const std::string& path) {
    const auto file = h5::File::open_read(path);
    const auto root = file.root();
    CollapseEvents events;
    events.inelasticity = (1.0 - root.attribute_double("restitution")) / 2.0;
    events.realizations = static_cast<std::size_t>(root.attribute_integer("realizations"));
    if (!root.has("collapse")) return events;
    const auto group = root.open_group("collapse");
    events.time = group.read_doubles("time");
    events.cluster_mass = group.read_doubles("cluster_mass");
    return events;
}

CollapseSummary summarize_collapse(const CollapseEvents& events) {
    CollapseSummary summary;
    summary.inelasticity = events.inelasticity;
    summary.collapsed = events.time.size();
    summary.realizations = events.realizations;
    if (events.time.size() < 2)
        throw InsufficientData("eps = " + std::to_string(events.inelasticity) + ": " +
                               std::to_string(events.time.size()) +
                               " realizations collapsed; an error bar needs 2 or more (more particles: collapse "
                               "needs N >~ ln(1/eps)/eps)");
    summary.time = mean_and_standard_error(events.time);
    summary.cluster_mass = mean_and_standard_error(events.cluster_mass);
    return summary;
}

LinearFit fit_against_inelasticity(const std::vector<double>& inelasticity, const std::vector<Estimate>& values) {
    std::vector<double> value, sigma;
    for (const auto& v : values) {
        value.push_back(v.value);
        sigma.push_back(v.sigma);
    }
    return fit_power_law(inelasticity, value, sigma);
}

}  // namespace shockgas::analysis
