// shockgas-merge: joins ensemble parts (shockgas-sim --first-realization k)
// into one file with the datasets a single run of all realizations writes; its
// root attributes are the run's (the first part's date and host), and
// merged_by, merged_date and merged_from say that and how it was merged.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "shockgas/cli/cli.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/io/output.hpp"
#include "shockgas/io/provenance.hpp"

int main(int argc, char** argv) {
    std::string output;
    std::vector<std::string> inputs;
    CLI::App app{"shockgas-merge: join ensemble parts made with --first-realization into one output file"};
    app.set_version_flag("--version", "shockgas-merge " + shockgas::build_info().version);
    app.add_option("-o,--output", output, "merged HDF5 file (written atomically)")->required();
    app.add_option("inputs", inputs, "part files, in realization order")->required()->check(CLI::ExistingFile);
    if (const int status = shockgas::cli::parse(app, argc, argv, "shockgas-merge"); status >= 0) return status;
    return shockgas::cli::run("shockgas-merge", [&] {
        shockgas::h5::check_writable(output);
        // The merged file is renamed over the output: a part named as the
        // output would be replaced by the merge.
        shockgas::h5::check_not_an_input(output, inputs);
        std::vector<shockgas::OutputFile> parts;
        for (const auto& input : inputs) {
            parts.push_back(shockgas::read_output(input));
            // The merged file records this program's provenance (its version and
            // simulator_sha256), so it must have the simulator that made the parts;
            // merged_from names each part's own version.
            if (!shockgas::made_by_this_simulator(parts.back().version, parts.back().simulator_sha256))
                throw shockgas::InputError(fmt::format(
                    "'{}' was made by {}, this is {}, another simulator: merge with a build of the simulator that ran "
                    "the parts",
                    input, shockgas::build_description(parts.back().version, parts.back().simulator_sha256),
                    shockgas::this_build_description()));
        }
        const auto merged = shockgas::merge_outputs(parts, inputs);
        // The parts' provenance (program, version, the first part's date and host), and
        // merged_by, merged_date and merged_from for this merge.
        shockgas::write_merged_output(output, merged, "shockgas-merge");
        fmt::print(stderr, "shockgas-merge: {} realization{} from {} part{} -> {} ({})\n", merged.result.realizations,
                   merged.result.realizations == 1 ? "" : "s", parts.size(), parts.size() == 1 ? "" : "s", output,
                   merged.result.status);
        return 0;
    });
}
