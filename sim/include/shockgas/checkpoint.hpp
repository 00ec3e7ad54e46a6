// Checkpoint integrity: where a run's checkpoints live, how they are saved and
// loaded, and who may use them. The format itself (the output schema plus
// /checkpoint) is written and read in output.hpp, with the output schema.
//
// - Two generations: saving renames the current checkpoint to PATH.previous
//   before the new one takes its name, so a damaged file has a fallback.
// - Loading verifies every checksum (h5::File::open_read) and the layout
//   against the run; a damaged or truncated checkpoint never ends a run: the
//   older generation is used, or the run starts from t = 0, with one warning
//   line saying which. Either way the result equals an uninterrupted run's.
// - A lock (PATH.lock, flock) lets one process at a time use a checkpoint.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "shockgas/output.hpp"
#include "shockgas/parameters.hpp"

namespace shockgas {

using Note = std::function<void(const std::string&)>;

// PATH.previous: the older generation of the checkpoint at path.
std::string previous_checkpoint_path(const std::string& path);

// Writes checkpoint to path atomically, keeping the one it replaces as the
// previous generation. Throws h5::Error naming path and the cause (full disk,
// file-size limit); the previous checkpoint is then kept untouched.
void save_checkpoint(const std::string& path, const Checkpoint& checkpoint);

// The newest usable checkpoint of the run with these parameters and sample
// times, from path or else its previous generation; nothing if there is none,
// or if it belongs to another run or code version (noted). A damaged one is
// passed over with one warning line through note.
std::optional<Checkpoint> load_checkpoint(const std::string& path, const SimulationParameters& parameters,
                                          const std::vector<double>& sample_times, const Note& note);

// Removes both generations (the output they served is safely written).
void remove_checkpoints(const std::string& path);

// An exclusive lock on the checkpoint at path, held while the object lives
// (flock on PATH.lock, released by the kernel if the process dies). Throws
// InputError if another live process holds it.
class CheckpointLock {
public:
    explicit CheckpointLock(const std::string& checkpoint_path);
    ~CheckpointLock();
    CheckpointLock(const CheckpointLock&) = delete;
    CheckpointLock& operator=(const CheckpointLock&) = delete;

private:
    std::string lock_path_;
    int descriptor_ = -1;
};

}  // namespace shockgas
