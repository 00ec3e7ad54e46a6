// SPDX-License-Identifier: GPL-3.0-or-later
// What the analysis programs write: a results file (HDF5 through shockgas::h5)
// of fitted numbers that carries provenance forward, and small
// whitespace-separated data files for gnuplot; and the checks every output
// path passes before any work starts.
#pragma once

#include <cstdio>
#include <initializer_list>
#include <string>
#include <vector>

#include "shockgas/analysis/fit.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/io/text_file.hpp"

namespace shockgas::analysis {

// How an analysis was asked for: enough to run it again. program names the
// subcommand ("shockgas-analyze shocks"), command_line is the command as
// given (each argument shell-quoted where needed), and options holds every
// option of the subcommand with the value it ran with, defaults included (an
// option with no default that was not given, e.g. --t-lo, is left out).
struct RecordedOption {
    std::string name;    // the long option without its dashes, '-' as '_' (--jump-fraction: jump_fraction)
    std::string value;   // as given or defaulted; a flag: true or false
    bool number = false; // stored as a number (a numeric option), else as text (paths, choices, flags)
};
struct AnalysisInvocation {
    std::string program;
    std::string command_line;
    std::vector<RecordedOption> options;
};

// Results file, written atomically. Root attributes: the analysis program's
// provenance (shockgas::write_provenance), command_line, and every root
// attribute of each input copied with prefix "input_" (one input) or
// "input<k>_" (several), plus input_path / input<k>_path. The group /options
// holds one attribute per option of the invocation (a number for a numeric
// option, else text): two results files with different options, e.g.
// --jump-fraction 2 and 1, differed only in their numbers before. Fitted
// numbers go into named groups as attributes: <name> and <name>_sigma for
// each Estimate.
class ResultsFile {
public:
    ResultsFile(const std::string& path, const AnalysisInvocation& invocation, const std::vector<std::string>& inputs);
    h5::Group root() const { return file_.root(); }
    h5::Group section(const std::string& name);
    void commit() { file_.commit(); }

private:
    h5::AtomicFile file_;
};

// A number that was not measured is stored as NaN with a <name>_note
// attribute giving the reason (a sigma alone: <name>_sigma_note), so that a
// reader of the file sees why; a measured number is stored alone.
void set_measured(h5::Group& group, const std::string& name, const Measured& value);
void set_estimate(h5::Group& group, const std::string& name, const Estimate& estimate);
// exponent, exponent_sigma, prefactor, chi2_per_dof, points of a log-log fit.
void set_power_law(h5::Group& group, const std::string& name, const LinearFit& fit);

// How every analysis program prints numbers that may be missing: the value in
// the fmt format spec ("{:.3f}"), or "n/a (<note>)". With a label, "0.012
// (jackknife)" or "n/a (jackknife: <note>)".
std::string format_measured(const Measured& value, const std::string& spec, const std::string& label = "");
// "value +- sigma", "value +- n/a (<note>)" or "n/a (<note>)"; sigma in
// sigma_spec when given, else in spec.
std::string format_estimate(const Estimate& estimate, const std::string& spec, const std::string& sigma_spec = "");

// A gnuplot data file: '#' lines (a description; the program, its version and
// `inputs`, the files it was computed from, as shockgas::provenance_comment
// writes them; for each input written by a simulator, its program,
// simulator_sha256 and seed; the column names), then one whitespace-separated row per call. Written as every text output
// is (shockgas::TextFile): beside the target and renamed onto it by commit(),
// removed if commit() is not reached, so that a failed run never leaves a
// table that looks complete; devices, FIFOs and links written through. A
// failure (full disk, file-size limit) throws InputError "cannot write data
// file 'TARGET': <reason>".
class DataFile {
public:
    DataFile(const std::string& path, const std::string& description, const std::vector<std::string>& inputs,
             const std::vector<std::string>& columns);
    void row(const std::vector<double>& values);
    void comment(const std::string& text);
    void blank_line();  // separates gnuplot data blocks (index)
    // Writes out what is buffered and closes the file (a full disk shows
    // here), keeping the temporary file until commit().
    void close() { file_.close(); }
    // close(), then renames the temporary file onto the target.
    void commit() { file_.commit(); }

private:
    TextFile file_;
};

// Throws (h5::Error or InputError, naming the path) unless a DataFile can be
// written at path (shockgas::check_text_writable).
void check_data_file_writable(const std::string& path);

// One output of an analysis run: the option that named it, the path (empty:
// not asked for), and whether it is a text data file or the results file.
struct OutputPath {
    std::string option;
    std::string path;
    bool text = true;
};

// Checks every output of one run before any work: each can be written
// (h5::check_writable, check_data_file_writable), none is one of the inputs
// (h5::check_not_an_input: writing it would destroy the input), and no two
// name the same file (one would overwrite the other; two devices may).
void check_outputs(const std::vector<OutputPath>& outputs, const std::vector<std::string>& inputs);

// Checks every input of one run before any work: none is a shockgas-sim
// checkpoint (PATH.checkpoint, a run in progress). It holds the output
// schema, so read as an output it would pass for a result of the run's first
// samples (status "checkpoint"); every subcommand refuses it here, with the
// words of shockgas::read_output. Nor is any a file that no subcommand reads
// (an analysis results file, an initial condition: shockgas::check_simulation_output);
// a far-tail sampler file passes, for far-tail, and the readers of a run
// refuse it.
// `expected` names what the subcommand reads, for the message ("'x.h5' is not <expected>: it is ...").
void check_inputs(const std::vector<std::string>& inputs, const std::string& expected = "a shockgas-sim output");

// Commits a run's outputs together: the data files are closed first (where a
// full disk shows), then the results file is committed, then the data files
// are renamed into place, so that a failure before the renames leaves none of
// them. Null pointers (outputs not asked for) are skipped.
void commit_outputs(ResultsFile* results, std::initializer_list<DataFile*> data_files);

}  // namespace shockgas::analysis
