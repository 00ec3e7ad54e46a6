// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-merge: joins ensemble parts (shockgas-sim or shockgas-spheres
// --first-realization k) into one file with the datasets a single run of all
// realizations writes; merged_by, merged_date and merged_from say that and how
// it was merged. Parses the paths and calls shockgas::merge_parts
// (shockgas/io/merge.hpp) or, for shockgas-spheres files,
// shockgas::spheres::merge_spheres_files (shockgas/spheres/job.hpp).
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "shockgas/cli/cli.hpp"
#include "shockgas/io/merge.hpp"
#include "shockgas/io/provenance.hpp"
#include "shockgas/spheres/ensemble.hpp"
#include "shockgas/spheres/job.hpp"

int main(int argc, char** argv) {
    std::string output;
    std::vector<std::string> inputs;
    CLI::App app{"shockgas-merge: join ensemble parts made with --first-realization into one output file"};
    app.set_version_flag("--version", "shockgas-merge " + shockgas::build_info().version);
    app.add_option("-o,--output", output, "merged HDF5 file (written atomically)")->required();
    app.add_option("inputs", inputs, "part files, in realization order")->required()->check(CLI::ExistingFile);
    if (const int status = shockgas::cli::parse(app, argc, argv, "shockgas-merge"); status >= 0) return status;
    return shockgas::cli::run("shockgas-merge", [&] {
        if (shockgas::spheres::is_spheres_output(inputs.front())) {
            const auto realizations = shockgas::spheres::merge_spheres_files(inputs, output, "shockgas-merge");
            fmt::print(stderr, "shockgas-merge: {}\n",
                       shockgas::merge_summary({realizations, inputs.size(), "complete"}, output));
            return 0;
        }
        const shockgas::MergeOutcome outcome = shockgas::merge_parts(inputs, output, "shockgas-merge");
        fmt::print(stderr, "shockgas-merge: {}\n", shockgas::merge_summary(outcome, output));
        return 0;
    });
}
