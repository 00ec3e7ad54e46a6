// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-dump's work (shockgas/analysis/dump.hpp).
#include "shockgas/analysis/dump.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>
#include <system_error>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "shockgas/io/h5.hpp"
#include "shockgas/io/output.hpp"
#include "shockgas/io/text_file.hpp"
#include "shockgas/model/parameters.hpp"

namespace shockgas {

namespace {

void collect_attributes(std::string& text, const h5::Group& group, const std::string& prefix, bool recursive) {
    auto out = std::back_inserter(text);
    for (const auto& name : group.attribute_names()) {
        try {
            // gnuplot knows NaN but not nan or inf: a non-finite number is written as NaN.
            const double value = group.attribute_double(name);
            if (std::isfinite(value))
                fmt::format_to(out, "{}_{} = {:.10g}\n", prefix, name, value);
            else
                fmt::format_to(out, "{}_{} = NaN\n", prefix, name);
        } catch (const h5::Error&) {
            try {
                std::string value = group.attribute_string(name);
                for (auto& c : value)
                    if (c == '"' || c == '\n') c = '\'';
                fmt::format_to(out, "{}_{} = \"{}\"\n", prefix, name, value);
            } catch (const h5::Error&) {
                // arrays and other kinds are not gnuplot scalars: skipped
            }
        }
    }
    if (!recursive) return;
    for (const auto& child : group.children())
        if (group.is_group(child)) collect_attributes(text, group.open_group(child), prefix + "_" + child, true);
}

}  // namespace

std::vector<ClusterState> read_realization_snapshots(const std::string& path, std::int64_t realization) {
    if (realization < 0) throw InputError(fmt::format("--realization must be >= 0, got {}", realization));
    const auto file = h5::File::open_read(path);
    const auto root = file.root();
    const std::vector<std::string> names =
        root.has("snapshots") ? root.open_group("snapshots").numbered_children() : std::vector<std::string>{};
    if (names.empty())
        throw InputError(
            fmt::format("'{}' has no snapshots (shockgas-sim stores them with --snapshot-times "
                        "or --snapshot-interval)",
                        path));
    if (root.has_attribute("realizations")) {
        const std::int64_t realizations = root.attribute_integer("realizations");
        if (realization >= realizations)
            throw InputError(fmt::format("--realization {}: '{}' has {} realization{} (0 to {})", realization, path,
                                         realizations, realizations == 1 ? "" : "s", realizations - 1));
    }
    const auto snapshots = root.open_group("snapshots");
    std::vector<ClusterState> states;
    std::set<std::int64_t> present;
    for (const auto& name : names) {
        const auto group = snapshots.open_group(name);
        const std::int64_t k = group.attribute_integer("realization");
        present.insert(k);
        if (k == realization) states.push_back(read_cluster_state(group, path));
    }
    if (states.empty())
        throw InputError(
            fmt::format("'{}' has no snapshot of realization {} (its snapshots are of "
                        "realization{} {})",
                        path, realization, present.size() == 1 ? "" : "s", fmt::join(present, ", ")));
    return states;
}

void write_snapshot_rows(std::FILE* out, const std::string& path, const std::vector<ClusterState>& states) {
    fmt::print(out, "# time position velocity mass first_particle  (from {})\n", path);
    for (const auto& state : states) {
        for (std::size_t i = 0; i < state.position.size(); ++i)
            fmt::print(out, "{:.9g} {:.12g} {:.9g} {:.9g} {}\n", state.time, state.position[i], state.velocity[i],
                       state.mass[i], state.first_particle[i]);
        fmt::print(out, "\n\n");
    }
}

std::string gnuplot_variables(const std::string& path, const std::string& group_path, const std::string& prefix,
                              bool recursive) {
    const auto file = h5::File::open_read(path);
    h5::Group group = file.root();
    std::size_t start = 0;
    while (start < group_path.size()) {
        const std::size_t end = std::min(group_path.find('/', start), group_path.size());
        if (end > start) group = group.open_group(group_path.substr(start, end - start));
        start = end + 1;
    }
    std::string text;
    collect_attributes(text, group, prefix, recursive);
    return text;
}

void run_dump(const DumpRequest& request) {
    const bool snapshots = request.kind == DumpRequest::Kind::snapshots;
    // The text would replace the input it is made from.
    if (!request.output.empty()) h5::check_not_an_input(request.output, {request.input});
    // Everything is read and checked first; only then is the output opened.
    std::vector<ClusterState> states;
    std::string text;
    if (snapshots)
        states = read_realization_snapshots(request.input, request.realization);
    else
        text = gnuplot_variables(request.input, request.group_path, request.prefix, request.recursive);
    // Standard output when no output is given; a file written beside its name and renamed (TextFile).
    TextFile out(request.output);
    try {
        if (snapshots)
            write_snapshot_rows(out.stream(), request.input, states);
        else
            fmt::print(out.stream(), "{}", text);
    } catch (const std::system_error& error) {  // fmt's failed fwrite (a full disk), with errno
        out.fail(error.code().value());
    }
    out.commit();
}

}  // namespace shockgas
