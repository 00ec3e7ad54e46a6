// Inelastic collapse of pure inelastic runs (delta = 0; P4): the time at which
// collapse stops a realization and the mass of the collapsing cluster, per
// file (one eps), and their power laws in eps. The paper's picture: collapse
// marks t_stick ~ eps^(-3/2), with cluster mass m ~ t_stick^(2/3) ~ eps^(-1).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "shockgas/analysis/fit.hpp"
#include "shockgas/ensemble.hpp"

namespace shockgas::analysis {

struct CollapseEvents {
    double inelasticity = 0.0;          // eps = (1 - r)/2
    std::size_t realizations = 0;       // realizations run
    std::vector<double> time;           // one entry per collapsed realization
    std::vector<double> cluster_mass;
};
CollapseEvents collapse_events_from(const EnsembleResult& result, double restitution);
CollapseEvents read_collapse_events(const std::string& path);

struct CollapseSummary {
    double inelasticity = 0.0;
    std::size_t collapsed = 0, realizations = 0;
    Estimate time;          // mean over collapsed realizations, SE from their scatter
    Estimate cluster_mass;  // likewise
};
CollapseSummary summarize_collapse(const CollapseEvents& events);

// Power law y = C eps^exponent over several eps (fit_power_law with the SEs as sigma).
LinearFit fit_against_inelasticity(const std::vector<double>& inelasticity, const std::vector<Estimate>& values);

}  // namespace shockgas::analysis
