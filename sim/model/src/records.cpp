// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/model/records.hpp"

#include <algorithm>
#include <iterator>
#include <limits>

namespace shockgas {

namespace {
// A sample time a realization did not reach.
constexpr double not_reached = std::numeric_limits<double>::quiet_NaN();
// One realization's counts: underflow, the bins between the edges, overflow.
std::size_t histogram_row(const HistogramRecord& h) { return h.edges.size() + 1; }
}  // namespace

void grow_realizations(EnsembleResult& r, std::int64_t realizations) {
    const auto rows = static_cast<std::size_t>(realizations);
    const std::size_t samples = r.times.size();
    for (const SampleTable table : sample_tables) (r.*table).resize(rows * samples, not_reached);
    r.realization_status.resize(rows, static_cast<std::int64_t>(RealizationStatus::not_run));
    r.engine_switch_time.resize(rows, std::numeric_limits<double>::quiet_NaN());
    for (HistogramRecord& h : r.histograms) h.counts.resize(rows * histogram_row(h), 0.0);
    r.realizations = realizations;
}

void copy_realization(const EnsembleResult& from, std::int64_t j, EnsembleResult& to, std::int64_t k) {
    const auto jj = static_cast<std::size_t>(j);
    const auto kk = static_cast<std::size_t>(k);
    const std::size_t samples = from.times.size();
    for (const SampleTable table : sample_tables)
        std::copy_n((from.*table).begin() + static_cast<std::ptrdiff_t>(jj * samples), samples,
                    (to.*table).begin() + static_cast<std::ptrdiff_t>(kk * samples));
    to.realization_status[kk] = from.realization_status[jj];
    to.engine_switch_time[kk] = from.engine_switch_time[jj];
    if (to.histograms.empty())
        for (const HistogramRecord& h : from.histograms)
            to.histograms.push_back(
                {h.time, h.edges, std::vector<double>(static_cast<std::size_t>(to.realizations) * histogram_row(h), 0.0)});
    for (std::size_t h = 0; h < to.histograms.size(); ++h) {
        const std::size_t bins = histogram_row(from.histograms[h]);
        std::copy_n(from.histograms[h].counts.begin() + static_cast<std::ptrdiff_t>(jj * bins), bins,
                    to.histograms[h].counts.begin() + static_cast<std::ptrdiff_t>(kk * bins));
    }
    // Records of k replaced in place: those of lower realizations stay before
    // them, of higher after (snapshots by (realization, time), collapses by
    // realization).
    const auto replace = [&](auto& records, const auto& source) {
        const auto first = std::partition_point(records.begin(), records.end(),
                                                [&](const auto& record) { return record.realization < k; });
        const auto last = std::partition_point(first, records.end(),
                                               [&](const auto& record) { return record.realization == k; });
        auto at = records.erase(first, last);
        for (auto record : source)
            if (record.realization == j) {
                record.realization = k;
                at = std::next(records.insert(at, std::move(record)));
            }
    };
    replace(to.snapshots, from.snapshots);
    replace(to.collapses, from.collapses);
}

}  // namespace shockgas
