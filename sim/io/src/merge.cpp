// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-merge's work (shockgas/io/merge.hpp).
#include "shockgas/io/merge.hpp"

#include <fmt/format.h>

#include "shockgas/io/h5.hpp"
#include "shockgas/io/output.hpp"
#include "shockgas/io/provenance.hpp"
#include "shockgas/model/parameters.hpp"

namespace shockgas {

MergeOutcome merge_parts(const std::vector<std::string>& inputs, const std::string& output,
                         const std::string& program) {
    h5::check_writable(output);
    // The merged file is renamed over the output: a part named as the output
    // would be replaced by the merge.
    h5::check_not_an_input(output, inputs);
    std::vector<OutputFile> parts;
    for (const auto& input : inputs) {
        parts.push_back(read_output(input));
        // The merged file records this program's provenance (its version and
        // simulator_sha256), so it must have the simulator that made the parts;
        // merged_from names each part's own version.
        if (!made_by_this_simulator(parts.back().version, parts.back().simulator_sha256))
            throw InputError(fmt::format(
                "'{}' was made by {}, this is {}, another simulator: merge with a build of the simulator that ran "
                "the parts",
                input, build_description(parts.back().version, parts.back().simulator_sha256),
                this_build_description()));
    }
    const auto merged = merge_outputs(parts, inputs);
    // The parts' provenance (program, version, the first part's date and host), and
    // merged_by, merged_date and merged_from for this merge.
    write_merged_output(output, merged, program);
    return {merged.result.realizations, parts.size(), merged.result.status};
}

std::string merge_summary(const MergeOutcome& outcome, const std::string& output) {
    return fmt::format("{} realization{} from {} part{} -> {} ({})", outcome.realizations,
                       outcome.realizations == 1 ? "" : "s", outcome.parts, outcome.parts == 1 ? "" : "s", output,
                       outcome.status);
}

}  // namespace shockgas
