// shockgas-dump: turns parts of HDF5 files into plain text for gnuplot.
//   snapshots FILE.h5 [--realization k]   rows "time position velocity mass first_particle",
//                                         one block (blank line) per snapshot
//   gnuplot-vars FILE.h5 GROUP --prefix P [--recursive]
//                                         each numeric attribute of GROUP as "P_name = value",
//                                         each string attribute as P_name = "value"
#include <cmath>
#include <cstdio>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "shockgas/cli.hpp"
#include "shockgas/h5.hpp"
#include "shockgas/output.hpp"
#include "shockgas/provenance.hpp"

namespace {

void dump_snapshots(std::FILE* out, const std::string& path, std::int64_t realization) {
    const auto file = shockgas::h5::File::open_read(path);
    const auto snapshots = file.root().open_group("snapshots");
    fmt::print(out, "# time position velocity mass first_particle  (from {})\n", path);
    for (const auto& name : snapshots.numbered_children()) {
        const auto group = snapshots.open_group(name);
        if (group.attribute_integer("realization") != realization) continue;
        const double time = group.attribute_double("time");
        const auto position = group.read_doubles("position");
        const auto velocity = group.read_doubles("velocity");
        const auto mass = group.read_doubles("mass");
        const auto first = group.read_integers("first_particle");
        for (std::size_t i = 0; i < position.size(); ++i)
            fmt::print(out, "{:.9g} {:.12g} {:.9g} {:.9g} {}\n", time, position[i], velocity[i], mass[i], first[i]);
        fmt::print(out, "\n\n");
    }
}

void dump_attributes(std::FILE* out, const shockgas::h5::Group& group, const std::string& prefix, bool recursive) {
    for (const auto& name : group.attribute_names()) {
        try {
            // gnuplot knows NaN but not nan or inf: a non-finite number is written as NaN.
            const double value = group.attribute_double(name);
            if (std::isfinite(value))
                fmt::print(out, "{}_{} = {:.10g}\n", prefix, name, value);
            else
                fmt::print(out, "{}_{} = NaN\n", prefix, name);
        } catch (const shockgas::h5::Error&) {
            try {
                std::string text = group.attribute_string(name);
                for (auto& c : text)
                    if (c == '"' || c == '\n') c = '\'';
                fmt::print(out, "{}_{} = \"{}\"\n", prefix, name, text);
            } catch (const shockgas::h5::Error&) {
                // arrays and other kinds are not gnuplot scalars: skipped
            }
        }
    }
    if (!recursive) return;
    for (const auto& child : group.children())
        if (group.is_group(child)) dump_attributes(out, group.open_group(child), prefix + "_" + child, true);
}

void dump_gnuplot_vars(std::FILE* out, const std::string& path, const std::string& group_path,
                       const std::string& prefix, bool recursive) {
    const auto file = shockgas::h5::File::open_read(path);
    shockgas::h5::Group group = file.root();
    std::size_t start = 0;
    while (start < group_path.size()) {
        const std::size_t end = std::min(group_path.find('/', start), group_path.size());
        if (end > start) group = group.open_group(group_path.substr(start, end - start));
        start = end + 1;
    }
    dump_attributes(out, group, prefix, recursive);
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
        std::FILE* out = stdout;
        if (!output.empty() && (out = std::fopen(output.c_str(), "w")) == nullptr)
            throw shockgas::InputError("cannot write '" + output + "'");
        if (*snapshots) dump_snapshots(out, input, realization);
        if (*vars) dump_gnuplot_vars(out, input, group_path, prefix, recursive);
        if (out != stdout && std::fclose(out) != 0) throw shockgas::InputError("cannot finish writing '" + output + "'");
        return 0;
    });
}
