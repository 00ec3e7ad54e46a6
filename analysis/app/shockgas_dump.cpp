// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-dump: turns parts of HDF5 files into plain text for gnuplot.
//   snapshots FILE.h5 [--realization k]   rows "time position velocity mass first_particle",
//                                         one block (blank line) per snapshot
//   gnuplot-vars FILE.h5 GROUP --prefix P [--recursive]
//                                         each numeric attribute of GROUP as "P_name = value",
//                                         each string attribute as P_name = "value"
// Binds the command line to a shockgas::DumpRequest and runs it (shockgas::run_dump,
// shockgas/analysis/dump.hpp), which reads and checks the input in full before the output is
// opened and leaves no output, nor a partial one, after a bad input or a failed write.
#include <string>

#include <CLI/CLI.hpp>

#include "shockgas/cli/cli.hpp"
#include "shockgas/analysis/dump.hpp"
#include "shockgas/io/provenance.hpp"

namespace {

struct Subcommands {
    CLI::App* snapshots;
    CLI::App* gnuplot_vars;
};

// Every option and subcommand, bound to the request's fields (their defaults are the request's).
Subcommands add_options(CLI::App& app, shockgas::DumpRequest& request) {
    app.set_version_flag("--version", "shockgas-dump " + shockgas::build_info().version);
    app.set_help_all_flag("--help-all", "print the options of every subcommand");
    app.require_subcommand(1);
    app.fallthrough();  // --output may follow the subcommand
    app.add_option("-o,--output", request.output, "write here instead of standard output");
    auto* snapshots = app.add_subcommand("snapshots", "every snapshot of one realization as text blocks");
    snapshots->add_option("input", request.input, "shockgas-sim output")->required()->check(CLI::ExistingFile);
    snapshots->add_option("--realization", request.realization, "which realization")->capture_default_str();
    auto* vars = app.add_subcommand("gnuplot-vars", "attributes of a group as gnuplot variables");
    vars->add_option("input", request.input, "HDF5 file")->required()->check(CLI::ExistingFile);
    vars->add_option("group", request.group_path, "group path, e.g. /decay")->required();
    vars->add_option("--prefix", request.prefix, "variable name prefix")->capture_default_str();
    vars->add_flag("--recursive", request.recursive, "also every subgroup, as PREFIX_<subgroup>_<name>");
    return {snapshots, vars};
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"shockgas-dump: HDF5 to plain text for gnuplot"};
    shockgas::DumpRequest request;
    const Subcommands subcommands = add_options(app, request);
    if (const int status = shockgas::cli::parse(app, argc, argv, "shockgas-dump"); status >= 0) return status;
    request.kind =
        *subcommands.snapshots ? shockgas::DumpRequest::Kind::snapshots : shockgas::DumpRequest::Kind::gnuplot_vars;
    return shockgas::cli::run("shockgas-dump", [&] {
        shockgas::run_dump(request);
        return 0;
    });
}
