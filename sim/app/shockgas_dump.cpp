// shockgas-dump: turns parts of HDF5 files into plain text for gnuplot.
//   snapshots FILE.h5 [--realization k]   rows "time position velocity mass first_particle",
//                                         one block (blank line) per snapshot
//   gnuplot-vars FILE.h5 GROUP --prefix P [--recursive]
//                                         each numeric attribute of GROUP as "P_name = value",
//                                         each string attribute as P_name = "value"
// The input is read and checked in full before the output is opened, and a
// file output is written beside its name and renamed into place when
// complete: a bad input or a failed write (a full disk) leaves no output, nor
// an empty or partial one that a plot would take for the real thing.
#include <cmath>
#include <cstdio>
#include <iterator>
#include <set>
#include <system_error>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "shockgas/cli/cli.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/io/output.hpp"
#include "shockgas/io/provenance.hpp"
#include "shockgas/io/text_file.hpp"

namespace {

// The snapshots of one realization, in file order, each checked to hold one
// value per cluster in every dataset (read_cluster_state). Refuses a
// realization the file does not have, and a file without snapshots, rather
// than print a header with nothing under it.
std::vector<shockgas::ClusterState> read_snapshots(const std::string& path, std::int64_t realization) {
    if (realization < 0) throw shockgas::InputError(fmt::format("--realization must be >= 0, got {}", realization));
    const auto file = shockgas::h5::File::open_read(path);
    const auto root = file.root();
    const std::vector<std::string> names =
        root.has("snapshots") ? root.open_group("snapshots").numbered_children() : std::vector<std::string>{};
    if (names.empty())
        throw shockgas::InputError(fmt::format("'{}' has no snapshots (shockgas-sim stores them with --snapshot-times "
                                               "or --snapshot-interval)",
                                               path));
    if (root.has_attribute("realizations")) {
        const std::int64_t realizations = root.attribute_integer("realizations");
        if (realization >= realizations)
            throw shockgas::InputError(fmt::format("--realization {}: '{}' has {} realization{} (0 to {})", realization,
                                                   path, realizations, realizations == 1 ? "" : "s",
                                                   realizations - 1));
    }
    const auto snapshots = root.open_group("snapshots");
    std::vector<shockgas::ClusterState> states;
    std::set<std::int64_t> present;
    for (const auto& name : names) {
        const auto group = snapshots.open_group(name);
        const std::int64_t k = group.attribute_integer("realization");
        present.insert(k);
        if (k == realization) states.push_back(shockgas::read_cluster_state(group, path));
    }
    if (states.empty())
        throw shockgas::InputError(fmt::format("'{}' has no snapshot of realization {} (its snapshots are of "
                                               "realization{} {})",
                                               path, realization, present.size() == 1 ? "" : "s",
                                               fmt::join(present, ", ")));
    return states;
}

void write_snapshots(std::FILE* out, const std::string& path, const std::vector<shockgas::ClusterState>& states) {
    fmt::print(out, "# time position velocity mass first_particle  (from {})\n", path);
    for (const auto& state : states) {
        for (std::size_t i = 0; i < state.position.size(); ++i)
            fmt::print(out, "{:.9g} {:.12g} {:.9g} {:.9g} {}\n", state.time, state.position[i], state.velocity[i],
                       state.mass[i], state.first_particle[i]);
        fmt::print(out, "\n\n");
    }
}

void collect_attributes(std::string& text, const shockgas::h5::Group& group, const std::string& prefix,
                        bool recursive) {
    auto out = std::back_inserter(text);
    for (const auto& name : group.attribute_names()) {
        try {
            // gnuplot knows NaN but not nan or inf: a non-finite number is written as NaN.
            const double value = group.attribute_double(name);
            if (std::isfinite(value))
                fmt::format_to(out, "{}_{} = {:.10g}\n", prefix, name, value);
            else
                fmt::format_to(out, "{}_{} = NaN\n", prefix, name);
        } catch (const shockgas::h5::Error&) {
            try {
                std::string value = group.attribute_string(name);
                for (auto& c : value)
                    if (c == '"' || c == '\n') c = '\'';
                fmt::format_to(out, "{}_{} = \"{}\"\n", prefix, name, value);
            } catch (const shockgas::h5::Error&) {
                // arrays and other kinds are not gnuplot scalars: skipped
            }
        }
    }
    if (!recursive) return;
    for (const auto& child : group.children())
        if (group.is_group(child)) collect_attributes(text, group.open_group(child), prefix + "_" + child, true);
}

std::string gnuplot_vars(const std::string& path, const std::string& group_path, const std::string& prefix,
                         bool recursive) {
    const auto file = shockgas::h5::File::open_read(path);
    shockgas::h5::Group group = file.root();
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

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"shockgas-dump: HDF5 to plain text for gnuplot"};
    app.set_version_flag("--version", "shockgas-dump " + shockgas::build_info().version);
    app.set_help_all_flag("--help-all", "print the options of every subcommand");
    app.require_subcommand(1);
    app.fallthrough();  // --output may follow the subcommand
    std::string input, group_path, prefix = "fit", output;
    app.add_option("-o,--output", output, "write here instead of standard output");
    std::int64_t realization = 0;
    auto* snapshots = app.add_subcommand("snapshots", "every snapshot of one realization as text blocks");
    snapshots->add_option("input", input, "shockgas-sim output")->required()->check(CLI::ExistingFile);
    snapshots->add_option("--realization", realization, "which realization")->capture_default_str();
    auto* vars = app.add_subcommand("gnuplot-vars", "attributes of a group as gnuplot variables");
    vars->add_option("input", input, "HDF5 file")->required()->check(CLI::ExistingFile);
    vars->add_option("group", group_path, "group path, e.g. /decay")->required();
    vars->add_option("--prefix", prefix, "variable name prefix")->capture_default_str();
    bool recursive = false;
    vars->add_flag("--recursive", recursive, "also every subgroup, as PREFIX_<subgroup>_<name>");
    if (const int status = shockgas::cli::parse(app, argc, argv, "shockgas-dump"); status >= 0) return status;
    return shockgas::cli::run("shockgas-dump", [&] {
        // The text would replace the input it is made from.
        if (!output.empty()) shockgas::h5::check_not_an_input(output, {input});
        // Everything is read and checked first; only then is the output opened.
        std::vector<shockgas::ClusterState> states;
        std::string text;
        if (*snapshots) states = read_snapshots(input, realization);
        if (*vars) text = gnuplot_vars(input, group_path, prefix, recursive);
        // Standard output when no -o; a file written beside its name and renamed (shockgas::TextFile).
        shockgas::TextFile out(output);
        try {
            if (*snapshots) write_snapshots(out.stream(), input, states);
            if (*vars) fmt::print(out.stream(), "{}", text);
        } catch (const std::system_error& error) {  // fmt's failed fwrite (a full disk), with errno
            out.fail(error.code().value());
        }
        out.commit();
        return 0;
    });
}
