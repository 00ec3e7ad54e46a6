// What the analysis programs write: a results file (HDF5 through shockgas::h5)
// of fitted numbers that carries provenance forward, and small
// whitespace-separated data files for gnuplot.
#pragma once

#include <fstream>
#include <string>
#include <vector>

#include "shockgas/analysis/fit.hpp"
#include "shockgas/h5.hpp"

namespace shockgas::analysis {

// Results file, written atomically. Root attributes: the analysis program's
// provenance (shockgas::write_provenance), and every root attribute of each
// input copied with prefix "input_" (one input) or "input<k>_" (several),
// plus input_path / input<k>_path. Fitted numbers go into named groups as
// attributes: <name> and <name>_sigma for each Estimate.
class ResultsFile {
public:
    ResultsFile(const std::string& path, const std::string& program, const std::vector<std::string>& inputs);
    h5::Group root() const { return file_.root(); }
    h5::Group section(const std::string& name);
    void commit() { file_.commit(); }

private:
    h5::AtomicFile file_;
};

void set_estimate(h5::Group& group, const std::string& name, const Estimate& estimate);
// exponent, exponent_sigma, prefactor, chi2_per_dof, points of a log-log fit.
void set_power_law(h5::Group& group, const std::string& name, const LinearFit& fit);

// A gnuplot data file: '#' lines (a description, then the column names),
// then one whitespace-separated row per call. Throws h5::Error-like
// std::runtime_error naming the path if it cannot be written.
class DataFile {
public:
    DataFile(const std::string& path, const std::string& description, const std::vector<std::string>& columns);
    void row(const std::vector<double>& values);
    void comment(const std::string& text);
    void blank_line();  // separates gnuplot data blocks (index)

private:
    std::ofstream out_;
    std::string path_;
};

}  // namespace shockgas::analysis
