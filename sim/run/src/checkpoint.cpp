// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/run/checkpoint.hpp"

#include <algorithm>
#include <cctype>
#include <array>
#include <limits>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <optional>
#include <filesystem>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "shockgas/io/h5.hpp"
#include "shockgas/io/provenance.hpp"

namespace shockgas {

std::string previous_checkpoint_path(const std::string& path) { return path + ".previous"; }

std::array<std::string, 2> checkpoint_generations(const std::string& path) {
    return {path, previous_checkpoint_path(path)};
}

void save_checkpoint(const std::string& path, const Checkpoint& checkpoint) {
    write_checkpoint(path, checkpoint, previous_checkpoint_path(path));
}

namespace {

// Whether what is at path may be treated as a checkpoint generation:
// nothing, a shockgas checkpoint, or an HDF5 file too damaged to tell (the
// damaged checkpoint --resume passes over). Anything else is another file
// that merely has the checkpoint's name.
bool may_be_checkpoint(const h5::Probe& found) {
    using Kind = h5::Probe::Kind;
    return found.kind == Kind::absent || found.kind == Kind::damaged ||
           (found.kind == Kind::hdf5 && found.holds("checkpoint"));
}

// The same for `file`, one generation of the checkpoint at `base`, knowing
// the others: an empty file holds nothing to lose, and a file that lost the
// HDF5 signature beside an intact shockgas checkpoint of another generation is
// a damaged generation of that run (another file that merely has the name
// would not have one beside it), which --resume passes over like any damaged
// checkpoint.
bool may_be_generation(const std::string& file, const std::string& base) {
    const h5::Probe found = h5::probe(file);
    if (may_be_checkpoint(found) || found.kind == h5::Probe::Kind::empty) return true;
    if (found.kind != h5::Probe::Kind::not_hdf5) return false;
    const auto generations = checkpoint_generations(base);
    return std::any_of(generations.begin(), generations.end(), [&](const std::string& other) {
        if (other == file) return false;
        const h5::Probe probed = h5::probe(other);
        return probed.kind == h5::Probe::Kind::hdf5 && probed.holds("checkpoint");
    });
}

// The checkpoint whose generation file is (PATH for PATH or PATH.previous).
std::string checkpoint_base(std::string file) {
    const std::string suffix = previous_checkpoint_path("");
    if (file.size() > suffix.size() && file.compare(file.size() - suffix.size(), suffix.size(), suffix) == 0)
        file.resize(file.size() - suffix.size());
    return file;
}

// Whether anything is at path, a dangling symbolic link included: true
// unless h5::probe would call it absent, found without opening the file.
bool anything_at(const std::string& path) {
    std::error_code error;
    const std::filesystem::file_status status = std::filesystem::symlink_status(path, error);
    return !error && std::filesystem::exists(status);
}

// Whether either generation of the checkpoint at base exists. It follows
// symbolic links (std::filesystem::exists), so a dangling link counts as
// no file.
bool any_generation_exists(const std::string& base) {
    const auto generations = checkpoint_generations(base);
    return std::any_of(generations.begin(), generations.end(),
                       [](const std::string& file) { return std::filesystem::exists(file); });
}

// A lock file holds the process id of its holder, or nothing.
bool may_be_lock(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code error;
    const fs::file_status status = fs::symlink_status(path, error);
    if (error || !fs::exists(status)) return true;
    if (!fs::is_regular_file(status) || fs::file_size(path, error) > 32 || error) return false;
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (file == nullptr) return false;
    char text[33] = {};
    const std::size_t length = std::fread(text, 1, 32, file);
    std::fclose(file);
    return std::string(text, length).find_first_not_of("0123456789\n") == std::string::npos;
}

// Whether a and b name one file: compared as files where both exist (another
// spelling, a hard link), else by their absolute, normalized names (a file
// about to be written by both).
bool same_file(const std::string& a, const std::string& b) {
    namespace fs = std::filesystem;
    std::error_code error;
    if (fs::exists(a, error) && fs::exists(b, error)) return fs::equivalent(a, b, error);
    const auto name = [](const std::string& path) {
        // Absolute first: weakly_canonical leaves a relative name whose
        // first component does not exist relative.
        std::error_code ignored;
        const fs::path absolute = fs::absolute(path, ignored).lexically_normal();
        const fs::path canonical = fs::weakly_canonical(absolute, ignored);
        return ignored ? absolute : canonical;
    };
    return name(a) == name(b);
}

}  // namespace

std::vector<std::string> remove_checkpoints(const std::string& path) {
    std::vector<std::string> kept;
    for (const std::string& file : checkpoint_generations(path)) {
        if (!anything_at(file)) continue;
        if (may_be_generation(file, path))
            std::remove(file.c_str());
        else
            kept.push_back(file);
    }
    return kept;
}

void check_checkpoint_path(const std::string& path, const std::vector<std::pair<std::string, std::string>>& others) {
    // A name ending in .previous is read as the older generation of the
    // checkpoint without that ending (checkpoint_base): its lock, its messages
    // and the clean-up after gathering would go to that other name.
    if (checkpoint_base(path) != path)
        throw InputError(fmt::format("checkpoint '{}' ends in '{}', the ending of a checkpoint's older generation, so "
                                     "it would be taken for one of '{}': give --checkpoint another path",
                                     path, previous_checkpoint_path(""), checkpoint_base(path)));
    // Every file the checkpoint writes or removes: both generations and the
    // lock. Each would destroy the run's output or init file of that name.
    const std::string previous = previous_checkpoint_path(path), lock = CheckpointLock::lock_path(path);
    for (const auto& [role, other] : others) {
        if (other.empty()) continue;
        std::string how;
        if (same_file(path, other))
            how = "is";
        else if (same_file(previous, other))
            how = fmt::format("keeps its older generation in '{}', which is", previous);
        else if (same_file(lock, other))
            how = fmt::format("is locked through '{}', which is", lock);
        if (!how.empty())
            throw InputError(fmt::format("checkpoint '{}' {} the {} '{}': give --checkpoint another path", path, how,
                                         role, other));
    }
    for (const std::string& file : checkpoint_generations(path)) {
        if (may_be_generation(file, path)) continue;
        const h5::Probe found = h5::probe(file);
        const char* what = found.kind == h5::Probe::Kind::not_regular ? "not a regular file"
                           : found.kind == h5::Probe::Kind::not_hdf5  ? "not an HDF5 file"
                                                                      : "an HDF5 file without /checkpoint";
        throw InputError(fmt::format("'{}' exists and is not a shockgas checkpoint ({}): the checkpoint would "
                                     "overwrite it; give --checkpoint another path",
                                     file, what));
    }
    if (!may_be_lock(lock))
        throw InputError(fmt::format("'{}' exists and is not a checkpoint lock: the checkpoint would overwrite it; "
                                     "give --checkpoint another path",
                                     lock));
}

namespace {

// Why a checkpoint that passed its checksums still cannot be continued by
// this run (its datasets do not have the run's shape); empty if it can.
std::string layout_problem(const Checkpoint& c, const SimulationParameters& p, const std::vector<double>& times) {
    const EnsembleResult& r = c.result;
    const auto realizations = static_cast<std::size_t>(p.realizations);
    const std::size_t cells = realizations * times.size();
    if (r.times != times) return "its sample times differ";
    for (const SampleTable table : sample_tables)
        if ((r.*table).size() != cells) return "its time series do not match its realizations and times";
    if (r.realization_status.size() != realizations || r.engine_switch_time.size() != realizations ||
        c.samples_done.size() != realizations)
        return "its realization records do not match the run's realizations";
    for (const std::int64_t done : c.samples_done)
        if (done < 0 || done > static_cast<std::int64_t>(times.size())) return "impossible samples_done";
    std::vector<double> histogram_times = p.histogram_times;
    std::sort(histogram_times.begin(), histogram_times.end());
    histogram_times.erase(std::unique(histogram_times.begin(), histogram_times.end()), histogram_times.end());
    if (r.histograms.size() != histogram_times.size()) return "its histograms do not match the run's";
    const auto bins = static_cast<std::size_t>(p.histogram_bins) + 2;
    for (const auto& histogram : r.histograms)
        if (histogram.counts.size() != realizations * bins) return "its histograms do not match the run's";
    return "";
}


// "3", "0..9": a block of realizations, for messages.
std::string realization_range(const SimulationParameters& p) {
    return p.realizations == 1 ? fmt::format("{}", p.first_realization)
                               : fmt::format("{}..{}", p.first_realization, p.first_realization + p.realizations - 1);
}

// Why `file`, a checkpoint generation, could not be read: the reader's message
// when it names the file, else "checkpoint 'FILE' is damaged: ...".
std::string damage_of(const std::string& file, const std::exception& error) {
    const std::string what = error.what();
    return what.find(file) != std::string::npos ? what : fmt::format("checkpoint '{}' is damaged: {}", file, what);
}

// "'a'", "'a' and 'b'", "'a', 'b' and 'c'": file names in a message.
std::string quoted_list(const std::vector<std::string>& files) {
    std::vector<std::string> names;
    for (const std::string& file : files) names.push_back(fmt::format("'{}'", file));
    if (names.size() == 1) return names.front();
    return fmt::format("{} and {}", fmt::join(names.begin(), names.end() - 1, ", "), names.back());
}

// "'a' and 'a.previous'", "'a', 'a.previous', 'b' and 'b.previous'": both
// generations of each checkpoint, for a message saying what to remove.
std::string both_generations(const std::vector<std::string>& bases) {
    std::vector<std::string> files;
    for (const std::string& base : bases)
        for (const std::string& file : checkpoint_generations(base)) files.push_back(file);
    return quoted_list(files);
}

// What makes checkpoint another run's than `run` ("t-max 500 vs 1000"), empty
// if none: check_checkpoint_of_run's rule.
std::string run_differences(const Checkpoint& checkpoint, const SimulationParameters& run, bool check_realizations) {
    std::vector<std::string> differences;
    if (std::string physics = parameter_differences(checkpoint.parameters, run); !physics.empty())
        differences.push_back(std::move(physics));
    const SimulationParameters& c = checkpoint.parameters;
    // Its engine states are one engine's: resumed under another, the file would name the one asked for
    // while its realizations ran the other. Both names are resolved
    // ("auto" never reaches here: the checkpoint stores the engine that ran).
    if (c.engine != run.engine) differences.push_back(fmt::format("engine {} vs {}", run.engine, c.engine));
    if (check_realizations && (c.first_realization < run.first_realization ||
                               c.first_realization + c.realizations > run.first_realization + run.realizations))
        differences.push_back(fmt::format("realizations {} vs {}", realization_range(run), realization_range(c)));
    return fmt::format("{}", fmt::join(differences, ", "));
}


// How far a checkpoint got: "t = 123.4 of 1000", "1 of 4 realizations done,
// the furthest at t = 80.5 of 1000" (the furthest engine, as resuming says).
std::string checkpoint_progress(const Checkpoint& checkpoint) {
    const SimulationParameters& c = checkpoint.parameters;
    double t = 0.0;
    for (const auto& [k, snapshot] : checkpoint.engines)
        if (const auto it = snapshot.reals.find("scalars"); it != snapshot.reals.end() && !it->second.empty())
            t = std::max(t, it->second.front());
    const auto& status = checkpoint.result.realization_status;
    const auto done = std::count_if(status.begin(), status.end(), [](std::int64_t s) {
        return s == static_cast<std::int64_t>(RealizationStatus::complete) ||
               s == static_cast<std::int64_t>(RealizationStatus::collapsed);
    });
    if (c.realizations == 1 && done == 0) return fmt::format("t = {:.6g} of {}", t, c.t_max);
    std::string text = fmt::format("{} of {} realizations done", done, c.realizations);
    if (!checkpoint.engines.empty()) text += fmt::format(", the furthest at t = {:.6g} of {}", t, c.t_max);
    return text;
}

// "2026-11-26 21:45 UTC": when file was last written.
std::string saved_at(const std::string& file) {
    struct stat info {};
    std::tm utc{};
    if (::stat(file.c_str(), &info) != 0 || gmtime_r(&info.st_mtime, &utc) == nullptr) return "at an unknown time";
    char text[32] = {};
    std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", &utc);
    return text;
}

}  // namespace

std::vector<std::string> check_no_interrupted_run(const std::vector<std::string>& files,
                                                  const SimulationParameters& run) {
    std::vector<std::string> warnings, bases;
    std::optional<std::pair<std::string, Checkpoint>> found;  // the first generation holding a run
    for (const std::string& name : files)
        for (const std::string& file : checkpoint_generations(name)) {
            const h5::Probe probed = h5::probe(file);
            if (probed.kind == h5::Probe::Kind::absent) continue;
            if (probed.kind != h5::Probe::Kind::damaged &&
                (probed.kind != h5::Probe::Kind::hdf5 || !probed.holds("checkpoint")))
                continue;  // not a checkpoint: check_checkpoint_path's refusal, where this run writes
            try {
                Checkpoint checkpoint = read_checkpoint(file);
                if (std::find(bases.begin(), bases.end(), checkpoint_base(file)) == bases.end())
                    bases.push_back(checkpoint_base(file));
                if (!found) found.emplace(file, std::move(checkpoint));
            } catch (const std::exception& error) {  // damaged, as load_checkpoint says it
                warnings.push_back(
                    fmt::format("warning: {}; it cannot be continued: starting from t = 0", damage_of(file, error)));
            }
        }
    if (!found) return warnings;
    const auto& [file, checkpoint] = *found;
    // A running process's checkpoint is not an interrupted run: say what the lock says.
    { const CheckpointLock running(checkpoint_base(file)); }
    const std::string remove = both_generations(bases);
    const std::string at = fmt::format("{}, saved {}", checkpoint_progress(checkpoint), saved_at(file));
    if (!made_by_this_simulator(checkpoint.version, checkpoint.simulator_sha256))
        throw InputError(fmt::format("'{}' holds an interrupted run of {} ({}), which only a build of that "
                                     "simulator can continue (this is {}, another simulator): remove {} to start anew",
                                     file, build_description(checkpoint.version, checkpoint.simulator_sha256), at,
                                     this_build_description(), remove));
    if (const std::string differences = run_differences(checkpoint, run, true); !differences.empty())
        throw InputError(fmt::format("'{}' holds an interrupted run with other parameters ({} in the checkpoint; {}): "
                                     "remove {} to start anew, or choose another -o/--checkpoint",
                                     file, differences, at, remove));
    throw InputError(fmt::format("'{}' holds an interrupted run ({}): continue it with --resume, or remove {} to start "
                                 "anew",
                                 file, at, remove));
}

void check_checkpoint_of_run(const std::string& file, const Checkpoint& checkpoint, const SimulationParameters& run,
                             bool check_realizations) {
    const std::string differences = run_differences(checkpoint, run, check_realizations);
    if (differences.empty()) return;
    throw InputError(fmt::format(
        "checkpoint '{}' belongs to a run with other parameters: {} in the checkpoint; --resume continues only "
        "the same run, so nothing was done: to continue it, give its parameters; to start anew, remove {}, or "
        "choose another -o/--checkpoint",
        file, differences, both_generations({checkpoint_base(file)})));
}

std::vector<std::string> job_checkpoints(const std::string& base, int ranks) {
    std::vector<std::string> files;
    if (ranks == 1) files.push_back(base);
    for (int k = 0; k < ranks && ranks > 1; ++k) files.push_back(rank_checkpoint_path(base, k));
    for (const auto& other : other_block_checkpoints(base, ""))
        if (std::find(files.begin(), files.end(), other) == files.end()) files.push_back(other);
    return files;
}

namespace {

// Each generation of the checkpoint `name` that exists and can be read, newest
// first. Damaged ones are left out: the loader passes over them with a warning.
// At most `wanted` of them: the newest alone says whose run a file holds, and a
// checkpoint can be tens of MB.
std::vector<std::pair<std::string, Checkpoint>> readable_generations(const std::string& name,
                                                                    std::size_t wanted = 2) {
    std::vector<std::pair<std::string, Checkpoint>> out;
    for (const std::string& file : checkpoint_generations(name)) {
        if (out.size() == wanted) break;
        if (!std::filesystem::exists(file)) continue;
        try {
            out.emplace_back(file, read_checkpoint(file));
        } catch (const std::exception&) {
        }
    }
    return out;
}

}  // namespace

void check_resume_checkpoints(const std::vector<std::string>& files, const SimulationParameters& run) {
    for (const std::string& name : files)
        for (const auto& [file, checkpoint] : readable_generations(name)) {
            if (!made_by_this_simulator(checkpoint.version, checkpoint.simulator_sha256))
                continue;  // ignored with a note when loaded
            check_checkpoint_of_run(file, checkpoint, run);
        }
}

bool is_finished_output_of_run(const std::string& output, const std::vector<std::string>& checkpoints,
                               const SimulationParameters& run) {
    for (const std::string& name : checkpoints)
        for (const std::string& file : checkpoint_generations(name))
            if (anything_at(file)) return false;  // --resume's to continue or refuse
    // The probe opens only a regular file (a FIFO would block, and a symbolic
    // link is no output: check_writable refuses both) and reads its signature
    // and names, which keeps read_output (which reads every dataset through)
    // from another program's large HDF5 file; what still cannot be read as an
    // output (damaged, a checkpoint) throws: it is not this run's result.
    const h5::Probe found = h5::probe(output);
    if (found.kind != h5::Probe::Kind::hdf5 || !found.holds("timeseries")) return false;
    try {
        const OutputFile existing = read_output(output);
        return existing.result.status != "interrupted" &&
               made_by_this_simulator(existing.version, existing.simulator_sha256) &&
               run_signature(existing.parameters) == run_signature(run) && existing.result.engine == run.engine;
    } catch (const std::exception&) {
        return false;  // damaged or not an output: replaced, as without --resume
    }
}

namespace {

// Both generations of the checkpoint at `path`, renamed to
// '<path>.from-<version>' (and its '.previous'), with a number added if that
// name is taken; returns the new names of those that existed.
std::vector<std::string> keep_aside(const std::string& path, const std::string& version) {
    std::string tag;
    for (char c : version) tag += std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' ? c : '_';
    std::string base = path + ".from-" + tag;
    for (int k = 2; any_generation_exists(base); ++k) base = fmt::format("{}.from-{}.{}", path, tag, k);
    std::vector<std::string> kept;
    const auto sources = checkpoint_generations(path), targets = checkpoint_generations(base);
    for (std::size_t k = 0; k < sources.size(); ++k) {
        const std::string &from = sources[k], &to = targets[k];
        std::error_code error;
        if (!std::filesystem::exists(from, error)) continue;
        std::filesystem::rename(from, to, error);
        if (error)
            throw InputError(fmt::format("cannot move the checkpoint '{}' aside to '{}': {}; move or remove it, then "
                                         "run again",
                                         from, to, error.message()));
        kept.push_back(to);
    }
    return kept;
}

// The name under which another simulator's checkpoint is kept: its version and,
// where recorded, the start of its simulator_sha256 (a version can name two
// simulators: two -dirty builds).
std::string aside_tag(const Checkpoint& checkpoint) {
    if (checkpoint.simulator_sha256.empty()) return checkpoint.version;
    return checkpoint.version + "-" + checkpoint.simulator_sha256.substr(0, 8);
}

}  // namespace

std::vector<std::string> set_aside_other_runs(const std::vector<std::string>& files, const SimulationParameters& run) {
    std::vector<std::string> notes;
    for (const std::string& name : files) {
        // The newest readable generation says whose run the file holds.
        const auto generations = readable_generations(name, 1);
        if (generations.empty()) continue;
        const auto& [file, checkpoint] = generations.front();
        // Another simulator's is moved aside by the loader, whatever its run.
        if (!made_by_this_simulator(checkpoint.version, checkpoint.simulator_sha256)) continue;
        const std::string differences = run_differences(checkpoint, run, true);
        if (differences.empty()) continue;
        // A running process's checkpoint is never moved: refused as the lock refuses it.
        const CheckpointLock running(checkpoint_base(file));
        const std::vector<std::string> kept = keep_aside(name, "other-run");
        notes.push_back(fmt::format("checkpoint '{}' belongs to a run with other parameters ({} in the checkpoint): "
                                    "moved aside to {}; this run does not continue it",
                                    name, differences, quoted_list(kept)));
    }
    return notes;
}

std::optional<Checkpoint> load_checkpoint(const std::string& path, const SimulationParameters& parameters,
                                          const std::vector<double>& sample_times, const Note& note,
                                          const SimulationParameters* whole_run, bool* another_block) {
    const auto say = [&](const std::string& text) {
        if (note) note(text);
    };
    namespace fs = std::filesystem;
    std::vector<std::string> damaged;  // one reason per damaged generation, newest first
    for (const std::string& candidate : checkpoint_generations(path)) {
        if (!fs::exists(candidate)) continue;
        Checkpoint checkpoint;
        try {
            checkpoint = read_checkpoint(candidate);
        } catch (const std::exception& error) {  // h5::Error (checksums, truncation) or InputError (layout)
            damaged.push_back(damage_of(candidate, error));
            continue;
        }
        // Another simulator continues nothing bit for bit, whatever run the
        // checkpoint holds (so this comes before the comparison of parameters,
        // whose refusal would say to give its parameters, which would not
        // continue it either): the run starts anew; but the hours in the old
        // checkpoint are moved aside, not overwritten by this run's first
        // checkpoint, so that a build of the simulator that wrote them can
        // still finish them.
        if (!made_by_this_simulator(checkpoint.version, checkpoint.simulator_sha256)) {
            const std::vector<std::string> kept = keep_aside(path, aside_tag(checkpoint));
            say(fmt::format("checkpoint '{}' was written by {}, this is {}, another simulator: starting from t = 0; "
                            "kept it as {} (a build of that simulator can continue it there with --checkpoint; "
                            "remove it when done)",
                            candidate, build_description(checkpoint.version, checkpoint.simulator_sha256),
                            this_build_description(), quoted_list(kept)));
            return std::nullopt;
        }
        // Another run: refused, before any work (the run would overwrite
        // it). Another block of this run: for gather_checkpoint.
        check_checkpoint_of_run(candidate, checkpoint, whole_run != nullptr ? *whole_run : parameters);
        if (checkpoint.signature != run_signature(parameters)) {
            if (another_block != nullptr) *another_block = true;
            say(fmt::format("checkpoint '{}' holds realizations {} of this run, not this block's {}; starting them "
                            "from t = 0",
                            candidate, realization_range(checkpoint.parameters), realization_range(parameters)));
            return std::nullopt;
        }
        if (const std::string problem = layout_problem(checkpoint, parameters, sample_times); !problem.empty()) {
            damaged.push_back(fmt::format("checkpoint '{}' does not fit this run: {}", candidate, problem));
            continue;
        }
        if (!damaged.empty())
            say(fmt::format("warning: {}; resuming from the previous checkpoint '{}'", damaged.front(), candidate));
        else if (candidate != path)
            say(fmt::format("'{}' is missing (killed while replacing it); resuming from the previous checkpoint '{}'",
                            path, candidate));
        if (checkpoint.version != build_info().version)
            say(fmt::format("checkpoint '{}' was written by {}, this is {}: the same simulator (sources, compiler "
                            "and flags), so it is continued",
                            candidate, build_description(checkpoint.version, checkpoint.simulator_sha256),
                            this_build_description()));
        return checkpoint;
    }
    if (damaged.size() == 1)
        say(fmt::format("warning: {}; no usable older checkpoint, starting from t = 0", damaged.front()));
    else if (damaged.size() == 2)
        say(fmt::format("warning: {}; so is the previous checkpoint ({}); starting from t = 0", damaged[0],
                        damaged[1]));
    return std::nullopt;
}

std::string rank_checkpoint_path(const std::string& base, int rank) { return fmt::format("{}.rank{}", base, rank); }

std::vector<std::string> other_block_checkpoints(const std::string& base, const std::string& own) {
    std::vector<std::string> found;
    for (int k = 0; any_generation_exists(rank_checkpoint_path(base, k)); ++k)
        if (rank_checkpoint_path(base, k) != own) found.push_back(rank_checkpoint_path(base, k));
    if (base != own && any_generation_exists(base)) found.push_back(base);
    return found;
}

void remove_gathered_checkpoints(const std::vector<std::string>& sources, const std::string& base, int ranks) {
    for (const std::string& source : sources) {
        const std::string file = checkpoint_base(source);
        bool current = ranks <= 1 && file == base;
        for (int k = 0; k < ranks && ranks > 1; ++k) current |= file == rank_checkpoint_path(base, k);
        if (!current) remove_checkpoints(file);
    }
}

std::optional<Checkpoint> gather_checkpoint(const std::vector<std::string>& candidates,
                                            const SimulationParameters& parameters,
                                            const std::vector<double>& sample_times, const Note& note,
                                            std::vector<std::string>* sources, const SimulationParameters* whole_run) {
    const auto say = [&](const std::string& text) {
        if (note) note(text);
    };
    const auto realizations = static_cast<std::size_t>(parameters.realizations);
    const std::string physics = physics_signature(parameters);

    Checkpoint out;
    out.parameters = parameters;
    out.version = build_info().version;
    out.simulator_sha256 = build_info().simulator_sha256;
    out.signature = run_signature(parameters);
    EnsembleResult& r = out.result;
    r.times = sample_times;
    grow_realizations(r, parameters.realizations);
    out.samples_done.assign(realizations, -1);  // -1: no candidate yet (0 after the loop)
    std::vector<std::string> taken_from(realizations);
    std::vector<double> cpu_seconds(realizations, 0.0), wall_seconds(realizations, 0.0);
    const auto finished = [](std::int64_t status) {
        return status == static_cast<std::int64_t>(RealizationStatus::complete) ||
               status == static_cast<std::int64_t>(RealizationStatus::collapsed);
    };
    // A finished record beats any in progress; then the one with more samples.
    const auto further = [&](std::int64_t status, std::int64_t done, std::int64_t other_status, std::int64_t other_done) {
        if (finished(status) != finished(other_status)) return finished(status);
        return done > other_done;
    };

    namespace fs = std::filesystem;
    for (const std::string& name : candidates)
        for (const std::string& candidate : checkpoint_generations(name)) {
            if (!fs::exists(candidate)) continue;
            Checkpoint c;
            try {
                c = read_checkpoint(candidate);
            } catch (const std::exception& error) {
                say(fmt::format("warning: passing over checkpoint '{}': {}", candidate, error.what()));
                continue;
            }
            if (c.signature != run_signature(c.parameters) || !made_by_this_simulator(c.version, c.simulator_sha256))
                continue;  // another simulator, or not a whole checkpoint
            // Another run: refused, as load_checkpoint does.
            check_checkpoint_of_run(candidate, c, whole_run != nullptr ? *whole_run : parameters, whole_run != nullptr);
            if (physics_signature(c.parameters) != physics || !layout_problem(c, c.parameters, sample_times).empty())
                continue;  // not a whole checkpoint
            // A file of this run: obsolete once the output is written, even
            // where another file's records of this block got further.
            if (sources != nullptr) sources->push_back(candidate);
            const std::int64_t offset = c.parameters.first_realization - parameters.first_realization;
            for (std::int64_t j = 0; j < c.result.realizations; ++j) {
                const std::int64_t k = j + offset;  // index in this block
                if (k < 0 || k >= parameters.realizations) continue;
                const auto jj = static_cast<std::size_t>(j);
                const auto kk = static_cast<std::size_t>(k);
                const std::int64_t status = c.result.realization_status[jj];
                const bool in_progress = status == static_cast<std::int64_t>(RealizationStatus::in_progress);
                // Usable as the ensemble's resume uses them: finished, or in
                // progress with its engine state.
                if (!finished(status) && !(in_progress && c.engines.count(j) > 0)) continue;
                if (out.samples_done[kk] >= 0 &&
                    !further(status, c.samples_done[jj], r.realization_status[kk], out.samples_done[kk]))
                    continue;
                copy_realization(c.result, j, r, k);
                out.samples_done[kk] = c.samples_done[jj];
                out.engines.erase(k);
                if (in_progress) out.engines.emplace(k, c.engines.at(j));
                // This block's share of the candidate's cost.
                const double share = 1.0 / static_cast<double>(c.result.realizations);
                cpu_seconds[kk] = share * c.result.cpu_seconds;
                wall_seconds[kk] = share * c.result.wall_seconds;
                taken_from[kk] = candidate;
            }
        }
    std::size_t found = 0;
    for (std::size_t k = 0; k < realizations; ++k) {
        if (out.samples_done[k] < 0) {
            out.samples_done[k] = 0;
            continue;
        }
        ++found;
        r.cpu_seconds += cpu_seconds[k];
        r.wall_seconds += wall_seconds[k];
    }
    if (found == 0) return std::nullopt;
    std::vector<std::string> files;
    for (const auto& f : taken_from)
        if (!f.empty() && std::find(files.begin(), files.end(), f) == files.end()) files.push_back(f);
    out.source = fmt::format("{}", fmt::join(files, "', '"));
    say(fmt::format("gathering {} of this block's {} realizations from checkpoints of other blocks of the same run "
                    "('{}')",
                    found, realizations, out.source));
    return out;
}

CheckpointLock::CheckpointLock(const std::string& checkpoint_path) : lock_path_(lock_path(checkpoint_path)) {
    // Open, lock, and check that the locked file is still the one at the
    // path: a holder that finished may have removed it between our open and
    // our lock, and a lock on a removed file protects nothing.
    for (;;) {
        descriptor_ = ::open(lock_path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (descriptor_ < 0)
            throw InputError(fmt::format("cannot create the checkpoint lock '{}': {}", lock_path_,
                                         std::strerror(errno)));
        if (::flock(descriptor_, LOCK_EX | LOCK_NB) != 0) {
            char holder[32] = {};
            const ssize_t length = ::pread(descriptor_, holder, sizeof holder - 1, 0);
            ::close(descriptor_);
            descriptor_ = -1;
            const std::string pid = length > 0 ? std::string(holder, static_cast<std::size_t>(length)) : "?";
            throw InputError(fmt::format("checkpoint '{}' is in use by another running shockgas-sim (process {}); "
                                         "two processes cannot continue one run",
                                         checkpoint_path, pid.substr(0, pid.find('\n'))));
        }
        struct stat opened {}, named {};
        if (::fstat(descriptor_, &opened) == 0 && ::stat(lock_path_.c_str(), &named) == 0 &&
            opened.st_ino == named.st_ino && opened.st_dev == named.st_dev)
            break;
        ::close(descriptor_);
    }
    const std::string pid = fmt::format("{}\n", ::getpid());
    if (::ftruncate(descriptor_, 0) == 0) {
        [[maybe_unused]] const ssize_t written = ::pwrite(descriptor_, pid.data(), pid.size(), 0);
    }
}

CheckpointLock::~CheckpointLock() {
    if (descriptor_ < 0) return;
    ::unlink(lock_path_.c_str());  // while still holding the lock: see the constructor
    ::close(descriptor_);
}

}  // namespace shockgas
