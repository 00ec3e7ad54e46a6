#include "shockgas/analysis/results.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <iomanip>
#include <stdexcept>

#include <fmt/format.h>

#include "shockgas/parameters.hpp"
#include "shockgas/provenance.hpp"

namespace shockgas::analysis {

ResultsFile::ResultsFile(const std::string& path, const std::string& program, const std::vector<std::string>& inputs)
    : file_(path) {
    auto root = file_.root();
    write_provenance(root, program);
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

void set_estimate(h5::Group& group, const std::string& name, const Estimate& estimate) {
    group.set_attribute(name, estimate.value);
    group.set_attribute(name + "_sigma", estimate.sigma);
}

void set_power_law(h5::Group& group, const std::string& name, const LinearFit& fit) {
    group.set_attribute(name + "_exponent", fit.slope);
    group.set_attribute(name + "_exponent_sigma", fit.slope_sigma());
    group.set_attribute(name + "_prefactor", std::exp(fit.intercept));
    group.set_attribute(name + "_chi2_per_dof", fit.chi2_per_dof());
    group.set_attribute(name + "_points", static_cast<std::int64_t>(fit.points));
}

DataFile::DataFile(const std::string& path, const std::string& description, const std::vector<std::string>& columns)
    : out_(path), path_(path) {
    if (!out_) throw InputError(fmt::format("cannot write data file '{}': {}", path, std::strerror(errno)));
    out_ << "# " << description << "\n#";
    for (const auto& column : columns) out_ << ' ' << column;
    out_ << '\n' << std::setprecision(10);
}

void DataFile::row(const std::vector<double>& values) {
    for (std::size_t i = 0; i < values.size(); ++i) out_ << (i ? " " : "") << values[i];
    out_ << '\n';
    if (!out_) throw std::runtime_error("write failed: " + path_);
}

void DataFile::comment(const std::string& text) { out_ << "# " << text << '\n'; }
void DataFile::blank_line() { out_ << "\n\n"; }

}  // namespace shockgas::analysis
