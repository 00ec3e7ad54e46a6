#include "shockgas/checkpoint.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "shockgas/h5.hpp"
#include "shockgas/provenance.hpp"

namespace shockgas {

std::string previous_checkpoint_path(const std::string& path) { return path + ".previous"; }

void save_checkpoint(const std::string& path, const Checkpoint& checkpoint) {
    write_checkpoint(path, checkpoint, previous_checkpoint_path(path));
}

void remove_checkpoints(const std::string& path) {
    std::remove(path.c_str());
    std::remove(previous_checkpoint_path(path).c_str());
}

namespace {

// Why a checkpoint that passed its checksums still cannot be continued by
// this run (its datasets do not have the run's shape); empty if it can.
std::string layout_problem(const Checkpoint& c, const SimulationParameters& p, const std::vector<double>& times) {
    const EnsembleResult& r = c.result;
    const auto realizations = static_cast<std::size_t>(p.realizations);
    const std::size_t cells = realizations * times.size();
    if (r.times != times) return "its sample times differ";
    for (const auto* table : {&r.temperature, &r.collisions_per_particle, &r.clusters, &r.kinetic_energy})
        if (table->size() != cells) return "its time series do not match its realizations and times";
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

}  // namespace

std::optional<Checkpoint> load_checkpoint(const std::string& path, const SimulationParameters& parameters,
                                          const std::vector<double>& sample_times, const Note& note) {
    const auto say = [&](const std::string& text) {
        if (note) note(text);
    };
    namespace fs = std::filesystem;
    const std::string previous = previous_checkpoint_path(path);
    std::vector<std::string> damaged;  // one reason per damaged generation, newest first
    for (const std::string& candidate : {path, previous}) {
        if (!fs::exists(candidate)) continue;
        Checkpoint checkpoint;
        try {
            checkpoint = read_checkpoint(candidate);
        } catch (const std::exception& error) {  // h5::Error (checksums, truncation) or InputError (layout)
            const std::string what = error.what();
            damaged.push_back(what.find(candidate) != std::string::npos
                                  ? what
                                  : fmt::format("checkpoint '{}' is damaged: {}", candidate, what));
            continue;
        }
        // Another run or code version: not damage, and its older generation
        // is of the same other run; start over, as before.
        if (checkpoint.signature != run_signature(parameters)) {
            say(fmt::format("ignoring checkpoint '{}': it belongs to a run with other parameters; starting from "
                            "t = 0 (it will be overwritten)",
                            candidate));
            return std::nullopt;
        }
        if (checkpoint.version != build_info().version) {
            say(fmt::format("ignoring checkpoint '{}': written by shockgas {}, this is {}; starting from t = 0",
                            candidate, checkpoint.version, build_info().version));
            return std::nullopt;
        }
        if (const std::string problem = layout_problem(checkpoint, parameters, sample_times); !problem.empty()) {
            damaged.push_back(fmt::format("checkpoint '{}' does not fit this run: {}", candidate, problem));
            continue;
        }
        if (!damaged.empty())
            say(fmt::format("warning: {}; resuming from the previous checkpoint '{}'", damaged.front(), candidate));
        else if (candidate == previous)
            say(fmt::format("'{}' is missing (killed while replacing it); resuming from the previous checkpoint '{}'",
                            path, candidate));
        return checkpoint;
    }
    if (damaged.size() == 1)
        say(fmt::format("warning: {}; no usable older checkpoint, starting from t = 0", damaged.front()));
    else if (damaged.size() == 2)
        say(fmt::format("warning: {}; so is the previous checkpoint ({}); starting from t = 0", damaged[0],
                        damaged[1]));
    return std::nullopt;
}

CheckpointLock::CheckpointLock(const std::string& checkpoint_path) : lock_path_(checkpoint_path + ".lock") {
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
