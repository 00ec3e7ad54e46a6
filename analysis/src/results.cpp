// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/analysis/results.hpp"

#include <cmath>
#include <string>
#include <filesystem>
#include <system_error>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "shockgas/io/output.hpp"
#include "shockgas/model/parameters.hpp"
#include "shockgas/io/provenance.hpp"

namespace shockgas::analysis {

ResultsFile::ResultsFile(const std::string& path, const AnalysisInvocation& invocation,
                         const std::vector<std::string>& inputs)
    : file_(path) {
    auto root = file_.root();
    write_provenance(root, invocation.program);
    root.set_attribute("command_line", invocation.command_line);
    auto options = root.create_group("options");
    for (const auto& option : invocation.options) {
        // A numeric option as a number (read back as one, e.g. by python),
        // whatever its spelling ("2", "2.0", "2e0"; the parser accepted it).
        if (option.number)
            options.set_attribute(option.name, std::stod(option.value));
        else
            options.set_attribute(option.name, option.value);
    }
    for (std::size_t k = 0; k < inputs.size(); ++k) {
        const std::string prefix = inputs.size() == 1 ? "input_" : "input" + std::to_string(k) + "_";
        const auto input = h5::File::open_read(inputs[k]);
        root.copy_attributes_from(input.root(), prefix);
        root.set_attribute(prefix + "path", inputs[k]);
    }
}

h5::Group ResultsFile::section(const std::string& name) {
    auto root = file_.root();
    return root.has(name) ? root.open_group(name) : root.create_group(name);
}

void set_measured(h5::Group& group, const std::string& name, const Measured& value) {
    group.set_attribute(name, value.value);
    if (!value.known()) group.set_attribute(name + "_note", value.note.empty() ? "not measured" : value.note);
}

void set_estimate(h5::Group& group, const std::string& name, const Estimate& estimate) {
    group.set_attribute(name, estimate.value);
    group.set_attribute(name + "_sigma", estimate.sigma);
    const std::string note = estimate.note.empty() ? "not measured" : estimate.note;
    if (std::isnan(estimate.value))
        group.set_attribute(name + "_note", note);
    else if (std::isnan(estimate.sigma))
        group.set_attribute(name + "_sigma_note", note);
}

void set_power_law(h5::Group& group, const std::string& name, const LinearFit& fit) {
    group.set_attribute(name + "_exponent", fit.slope);
    group.set_attribute(name + "_exponent_sigma", fit.slope_sigma());
    group.set_attribute(name + "_prefactor", std::exp(fit.intercept));
    set_measured(group, name + "_chi2_per_dof", fit.reduced_chi2());
    group.set_attribute(name + "_points", static_cast<std::int64_t>(fit.points));
}

std::string format_measured(const Measured& value, const std::string& spec, const std::string& label) {
    const std::string note = value.note.empty() ? "not measured" : value.note;
    if (!value.known()) return label.empty() ? "n/a (" + note + ")" : "n/a (" + label + ": " + note + ")";
    const std::string number = fmt::format(fmt::runtime(spec), value.value);
    return label.empty() ? number : number + " (" + label + ")";
}

std::string format_estimate(const Estimate& estimate, const std::string& spec, const std::string& sigma_spec) {
    if (std::isnan(estimate.value)) return format_measured({estimate.value, estimate.note}, spec);
    return fmt::format(fmt::runtime(spec), estimate.value) + " +- " +
           format_measured({estimate.sigma, estimate.note}, sigma_spec.empty() ? spec : sigma_spec);
}

namespace {

// How every data file names itself in messages: "cannot write data file 'x.dat': ...".
const std::string data_file_kind = "data file ";

// One '#' line per HDF5 input that our programs wrote (write_provenance: a
// program and a simulator_sha256, always together): the program, the source
// hash and, for a run, its seed. A table then names the simulation its numbers
// came from, not only a path that a later run may overwrite, as the results
// files do with their input_* attributes. Not the git version: the same
// simulator built at another commit makes the same numbers, and
// tools/reproduce-check compares tables byte for byte. Inputs that are not
// HDF5 (a T(t) table) or carry no hash add nothing.
std::string input_provenance_lines(const std::vector<std::string>& inputs) {
    std::string lines;
    for (const auto& input : inputs) {
        if (h5::probe(input).kind != h5::Probe::Kind::hdf5) continue;
        const auto file = h5::File::open_read(input);
        const auto root = file.root();
        if (!root.has_attribute("simulator_sha256")) continue;
        std::string line = fmt::format("# input {}: {}, simulator_sha256 {}", input, root.attribute_string("program"),
                                       root.attribute_string("simulator_sha256"));
        if (root.has_attribute("seed")) line += fmt::format(", seed {}", root.attribute_integer("seed"));
        lines += line + '\n';
    }
    return lines;
}

}  // namespace

void check_data_file_writable(const std::string& path) { check_text_writable(path, data_file_kind); }

void check_outputs(const std::vector<OutputPath>& outputs, const std::vector<std::string>& inputs) {
    namespace fs = std::filesystem;
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        const OutputPath& output = outputs[i];
        if (output.path.empty()) continue;
        if (output.text)
            check_data_file_writable(output.path);
        else
            h5::check_writable(output.path);
        h5::check_not_an_input(output.path, inputs);
        // Two outputs at one path: the second written would replace the first.
        // Devices (/dev/null twice) take both.
        if (writes_through(output.path)) continue;
        // Absolute first: weakly_canonical leaves a relative path whose first
        // element does not exist as it is, so "t.dat" and "./t.dat" differed.
        auto resolved = [](const std::string& path) {
            std::error_code error;
            return fs::weakly_canonical(fs::absolute(path, error), error);
        };
        const fs::path here = resolved(output.path);
        for (std::size_t j = 0; j < i; ++j) {
            const OutputPath& other = outputs[j];
            if (other.path.empty() || writes_through(other.path)) continue;
            if (resolved(other.path) == here)
                throw InputError(fmt::format("{} and {} name the same file '{}': one would overwrite the other",
                                             other.option, output.option, output.path));
        }
    }
}

DataFile::DataFile(const std::string& path, const std::string& description, const std::vector<std::string>& inputs,
                   const std::vector<std::string>& columns)
    // Checked before the file is opened: a missing directory is named as every output's is.
    : file_((check_data_file_writable(path), path), data_file_kind) {
    // Not dated: a rerun of the same code gives the same table (tools/reproduce-check compares them byte for byte).
    std::string header = "# " + description + "\n" +
                         provenance_comment("shockgas-analyze", fmt::format("{}", fmt::join(inputs, ", ")),
                                            false) +
                         input_provenance_lines(inputs) + "#";
    for (const auto& column : columns) header += ' ' + column;
    file_.write(header + '\n');
}

void DataFile::row(const std::vector<double>& values) {
    std::string line;
    for (std::size_t i = 0; i < values.size(); ++i) line += fmt::format("{}{:.10g}", i ? " " : "", values[i]);
    file_.write(line + '\n');
}

void DataFile::comment(const std::string& text) { file_.write("# " + text + '\n'); }
void DataFile::blank_line() { file_.write("\n\n"); }

void check_inputs(const std::vector<std::string>& inputs, const std::string& expected) {
    for (const auto& input : inputs) {
        const h5::Probe found = h5::probe(input);
        if (found.kind != h5::Probe::Kind::hdf5) continue;  // its reader names what it is not
        if (found.holds("checkpoint")) throw checkpoint_given_as_output(input);
        // A results file given for a run is named as such (a reader would otherwise say only
        // "missing attribute /restitution"). A far-tail file is far-tail's input; any other subcommand's reader of a
        // run (read_output, read_timeseries) refuses it as check_simulation_output words it.
        const auto file = h5::File::open_read(input);
        const auto root = file.root();
        if (is_far_tail_file(root)) continue;
        if (const std::string other = other_kind_of_file(root); !other.empty())
            throw InputError(fmt::format("'{}' is not {}: it is {}", input, expected, other));
    }
}

void commit_outputs(ResultsFile* results, std::initializer_list<DataFile*> data_files) {
    for (DataFile* file : data_files)
        if (file != nullptr) file->close();
    if (results != nullptr) results->commit();
    for (DataFile* file : data_files)
        if (file != nullptr) file->commit();
}

}  // namespace shockgas::analysis
