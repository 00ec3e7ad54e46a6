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
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <set>
#include <system_error>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "shockgas/cli.hpp"
#include "shockgas/h5.hpp"
#include "shockgas/output.hpp"
#include "shockgas/provenance.hpp"

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

// Where the text goes: standard output; a regular file (or a new one),
// written as PATH.tmp.<pid> and renamed onto PATH by commit(); or something
// else that already exists (/dev/null, /dev/stdout, a FIFO, a symbolic link),
// written through, since renaming over it would replace the device or link
// itself. Every failure (open, write, flush, close) is an InputError naming
// the output and the system's reason; the temporary file is then removed.
class TextOutput {
public:
    explicit TextOutput(std::string path) : path_(std::move(path)) {
        if (path_.empty()) {
            stream_ = stdout;
            return;
        }
        namespace fs = std::filesystem;
        std::error_code error;
        const fs::file_status status = fs::symlink_status(path_, error);
        const bool through = !error && fs::exists(status) && !fs::is_regular_file(status);
        if (!through) temporary_ = path_ + ".tmp." + std::to_string(::getpid());
        stream_ = std::fopen(through ? path_.c_str() : temporary_.c_str(), "w");
        if (stream_ == nullptr) fail(errno);
    }
    TextOutput(const TextOutput&) = delete;
    TextOutput& operator=(const TextOutput&) = delete;
    ~TextOutput() {
        if (stream_ != nullptr && stream_ != stdout) std::fclose(stream_);
        if (!temporary_.empty()) std::remove(temporary_.c_str());
    }

    std::FILE* stream() const { return stream_; }

    // Writes out what the stream still buffers and checks that every byte got
    // there: `-o /dev/full` and `> /dev/full` fail here (ENOSPC), not in silence.
    void commit() {
        errno = 0;
        const bool flushed = std::fflush(stream_) == 0 && std::ferror(stream_) == 0;
        int reason = errno;
        if (flushed && !temporary_.empty() && ::fsync(::fileno(stream_)) != 0) fail(errno);
        if (!flushed) fail(reason != 0 ? reason : EIO);
        if (stream_ == stdout) return;
        std::FILE* stream = stream_;
        stream_ = nullptr;
        errno = 0;
        if (std::fclose(stream) != 0) fail(errno != 0 ? errno : EIO);
        if (temporary_.empty()) return;
        if (std::rename(temporary_.c_str(), path_.c_str()) != 0) fail(errno);
        temporary_.clear();
    }

    [[noreturn]] void fail(int reason) const {
        throw shockgas::InputError(fmt::format("cannot write {}: {}",
                                               path_.empty() ? std::string("standard output") : "'" + path_ + "'",
                                               std::strerror(reason)));
    }

private:
    std::string path_;
    std::string temporary_;  // empty: written in place (standard output, a device)
    std::FILE* stream_ = nullptr;
};

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
        TextOutput out(output);
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
