// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/spheres/ensemble.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <ctime>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <cstdio>
#include <thread>

#include <fmt/format.h>

#include "shockgas/io/h5.hpp"
#include "shockgas/io/provenance.hpp"
#include "shockgas/run/checkpoint.hpp"
#include "shockgas/spheres/start.hpp"

namespace shockgas::spheres {

namespace {

double process_cpu_seconds() {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

bool listed(const std::vector<double>& times, double t) {
    return std::find(times.begin(), times.end(), t) != times.end();
}

// The coarse-grained density and velocity of one realization (SphereSnapshot).
void coarse_fields(const SphereState& state, int cells_per_side, double* density, double* velocity_field) {
    const int d = state.dimension;
    std::size_t cells = 1;
    for (int k = 0; k < d; ++k) cells *= static_cast<std::size_t>(cells_per_side);
    std::vector<double> count(cells, 0.0);
    std::fill(velocity_field, velocity_field + cells * static_cast<std::size_t>(d), 0.0);
    const double width = state.box_length / cells_per_side;
    const std::size_t n = static_cast<std::size_t>(state.particles());
    for (std::size_t i = 0; i < n; ++i) {
        std::size_t index = 0;
        for (int k = d - 1; k >= 0; --k) {
            const int c = std::min(cells_per_side - 1,
                                   static_cast<int>(state.positions[i * static_cast<std::size_t>(d) + static_cast<std::size_t>(k)] / width));
            index = index * static_cast<std::size_t>(cells_per_side) + static_cast<std::size_t>(c);
        }
        count[index] += 1.0;
        for (int k = 0; k < d; ++k)
            velocity_field[index * static_cast<std::size_t>(d) + static_cast<std::size_t>(k)] +=
                state.velocities[i * static_cast<std::size_t>(d) + static_cast<std::size_t>(k)];
    }
    const double mean_count = static_cast<double>(n) / static_cast<double>(cells);
    for (std::size_t c = 0; c < cells; ++c) {
        density[c] = count[c] / mean_count;
        if (count[c] > 0.0)
            for (int k = 0; k < d; ++k) velocity_field[c * static_cast<std::size_t>(d) + static_cast<std::size_t>(k)] /= count[c];
    }
}

}  // namespace

double thread_cpu_seconds() {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

double velocity_kurtosis(const std::vector<double>& v, int d) {
    const auto mean = mean_velocity(v, d);
    double second = 0.0, fourth = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) {
        const double u = v[i] - mean[i % static_cast<std::size_t>(d)];
        second += u * u;
        fourth += u * u * u * u;
    }
    const double count = static_cast<double>(v.size());
    return (fourth / count) / ((second / count) * (second / count));
}

namespace {

// What the checkpoint holds of one realization: how many samples it has
// taken, its rows so far, and its engine (absent once it has finished).
struct RealizationRecord {
    std::int64_t samples_done = 0;
    bool finished = false;
    std::string status = "complete";
    double end_time = 0.0;
    double start_seconds = 0.0;
    std::vector<double> temperature, collisions_per_particle, velocity_kurtosis;  // samples_done each
    std::vector<std::vector<double>> histogram_rows;                              // those taken
    std::vector<std::vector<double>> density, velocity_field;                     // snapshots taken
    std::vector<std::vector<double>> positions, velocities;                       // realization 0's snapshots
    CollisionCounts counts;
    bool has_engine = false;
    EngineRecord engine;
};

constexpr const char* checkpoint_schema = "spheres-checkpoint";

// A checkpoint of another build of the engine: passed over (the run starts
// anew, as shockgas-sim does with another simulator's checkpoint), not refused.
struct OtherSimulator : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// cpu_seconds: the run's CPU time so far, this process's and that of the runs it continues.
void write_checkpoint(const std::string& path, const SphereParameters& p,
                      const std::vector<std::optional<RealizationRecord>>& book, double cpu_seconds) {
    h5::write_atomically(
        path,
        [&](h5::Group& root) {
            write_provenance(root, "shockgas-spheres");
            root.set_attribute("spheres_sha256", spheres_sha256());
            root.set_attribute("schema", checkpoint_schema);
            root.set_attribute("cpu_seconds", cpu_seconds);
            write_parameter_attributes(root, p);
            auto all = root.create_group("realizations");
            for (std::size_t r = 0; r < book.size(); ++r) {
                if (!book[r]) continue;
                const RealizationRecord& record = *book[r];
                auto g = all.create_group(h5::numbered_name(r, book.size()));
                g.set_attribute("samples_done", record.samples_done);
                g.set_attribute("finished", static_cast<std::int64_t>(record.finished ? 1 : 0));
                g.set_attribute("status", record.status);
                g.set_attribute("end_time", record.end_time);
                g.set_attribute("start_seconds", record.start_seconds);
                g.write("counts", std::vector<std::int64_t>{static_cast<std::int64_t>(record.counts.inelastic),
                                                           static_cast<std::int64_t>(record.counts.elastic),
                                                           static_cast<std::int64_t>(record.counts.cell_crossings),
                                                           static_cast<std::int64_t>(record.counts.stale_events)});
                if (record.samples_done > 0) {
                    g.write("temperature", record.temperature);
                    g.write("collisions_per_particle", record.collisions_per_particle);
                    g.write("velocity_kurtosis", record.velocity_kurtosis);
                }
                auto write_rows = [&](const std::string& name, const std::vector<std::vector<double>>& rows) {
                    auto group = g.create_group(name);
                    for (std::size_t i = 0; i < rows.size(); ++i)
                        if (!rows[i].empty()) group.write(h5::numbered_name(i, rows.size()), rows[i]);
                };
                write_rows("histogram_rows", record.histogram_rows);
                write_rows("density", record.density);
                write_rows("velocity_field", record.velocity_field);
                write_rows("positions", record.positions);
                write_rows("velocities", record.velocities);
                if (record.has_engine) {
                    auto e = g.create_group("engine");
                    e.set_attribute("dimension", static_cast<std::int64_t>(record.engine.dimension));
                    e.set_attribute("box_length", record.engine.box_length);
                    e.set_attribute("time", record.engine.time);
                    e.write("reals", record.engine.reals);
                    e.write("integers", record.engine.integers);
                }
            }
        },
        previous_checkpoint_path(path));
}

std::vector<std::optional<RealizationRecord>> read_checkpoint(const std::string& path, const SphereParameters& p,
                                                              double& cpu_seconds) {
    const auto file = h5::File::open_read(path);
    const auto root = file.root();
    if (!root.has_attribute("schema") || root.attribute_string("schema") != checkpoint_schema)
        throw InputError(fmt::format("{} is not a checkpoint of shockgas-spheres", path));
    if (root.attribute_string("spheres_sha256") != spheres_sha256())
        throw OtherSimulator(fmt::format("{} was written by another version of the disk and sphere engine "
                                         "(spheres_sha256 {} vs this build's {}), which would not continue it "
                                         "bit for bit",
                                         path, root.attribute_string("spheres_sha256").substr(0, 12),
                                         spheres_sha256().substr(0, 12)));
    const auto differences = parameter_differences(p, read_parameter_attributes(root));
    if (!differences.empty())
        throw InputError(fmt::format("{} is the checkpoint of another run ({} in the checkpoint); remove it to "
                                     "start anew",
                                     path, fmt::join(differences, ", ")));
    std::vector<std::optional<RealizationRecord>> book(static_cast<std::size_t>(p.realizations));
    cpu_seconds = root.attribute_double("cpu_seconds");
    const auto all = root.open_group("realizations");
    for (const auto& name : all.children()) {
        const auto r = static_cast<std::size_t>(std::stoll(name));
        const auto g = all.open_group(name);
        RealizationRecord record;
        record.samples_done = g.attribute_integer("samples_done");
        record.finished = g.attribute_integer("finished") != 0;
        record.status = g.attribute_string("status");
        record.end_time = g.attribute_double("end_time");
        record.start_seconds = g.attribute_double("start_seconds");
        const auto counts = g.read_integers("counts");
        record.counts = {static_cast<std::uint64_t>(counts[0]), static_cast<std::uint64_t>(counts[1]),
                         static_cast<std::uint64_t>(counts[2]), static_cast<std::uint64_t>(counts[3])};
        if (record.samples_done > 0) {
            record.temperature = g.read_doubles("temperature");
            record.collisions_per_particle = g.read_doubles("collisions_per_particle");
            record.velocity_kurtosis = g.read_doubles("velocity_kurtosis");
        }
        auto read_rows = [&](const std::string& group_name, std::vector<std::vector<double>>& rows) {
            const auto group = g.open_group(group_name);
            for (const auto& row : group.numbered_children()) {
                const auto i = static_cast<std::size_t>(std::stoll(row));
                if (rows.size() <= i) rows.resize(i + 1);
                rows[i] = group.read_doubles(row);
            }
        };
        read_rows("histogram_rows", record.histogram_rows);
        read_rows("density", record.density);
        read_rows("velocity_field", record.velocity_field);
        read_rows("positions", record.positions);
        read_rows("velocities", record.velocities);
        if (g.has("engine")) {
            const auto e = g.open_group("engine");
            record.has_engine = true;
            record.engine.dimension = static_cast<int>(e.attribute_integer("dimension"));
            record.engine.box_length = e.attribute_double("box_length");
            record.engine.time = e.attribute_double("time");
            record.engine.reals = e.read_doubles("reals");
            record.engine.integers = e.read_integers("integers");
        }
        if (r < book.size()) book[r] = std::move(record);
    }
    return book;
}

}  // namespace

void remove_spheres_checkpoint(const std::string& checkpoint) {
    if (checkpoint.empty()) return;
    for (const auto& path : checkpoint_generations(checkpoint)) std::remove(path.c_str());
}

SphereResult run_spheres(const SphereParameters& p, const ProgressCallback& progress, const SphereRunOptions& options) {
    validate(p);
    const auto wall_start = std::chrono::steady_clock::now();
    const double cpu_start = process_cpu_seconds();
    const int d = p.dimension;
    const auto note = [&](const std::string& text) {
        if (options.note) options.note(text);
    };
    SphereResult result;
    result.time = sample_grid(p);
    result.realizations = p.realizations;
    const std::size_t samples = result.time.size();
    const auto realizations = static_cast<std::size_t>(p.realizations);
    std::size_t field_cells = 1;
    for (int k = 0; k < d; ++k) field_cells *= static_cast<std::size_t>(p.field_cells);
    std::vector<double> histogram_times, snapshot_times;
    for (double t : result.time) {
        if (listed(p.histogram_times, t)) histogram_times.push_back(t);
        if (listed(p.snapshot_times, t)) snapshot_times.push_back(t);
    }
    const auto bins = static_cast<std::size_t>(p.histogram_bins);

    // The book: each realization's record, filled as it runs, read from the
    // checkpoint when resuming. A thread touches only its own entry but under
    // the lock, since the checkpoint writer reads them all.
    std::vector<std::optional<RealizationRecord>> book(realizations);
    std::optional<CheckpointLock> lock_file;
    double previous_cpu_seconds = 0.0;  // of the runs a resumed checkpoint continues
    if (!options.checkpoint.empty()) {
        lock_file.emplace(options.checkpoint);
        const auto generations = checkpoint_generations(options.checkpoint);
        if (!options.resume) {
            for (const auto& path : generations)
                if (h5::probe(path).kind != h5::Probe::Kind::absent)
                    throw InputError(fmt::format("{} holds the checkpoint of an interrupted run: continue it with "
                                                 "--resume, or remove it to start anew",
                                                 path));
        } else {
            bool loaded = false;
            for (const auto& path : generations) {
                if (h5::probe(path).kind == h5::Probe::Kind::absent) continue;
                try {
                    book = read_checkpoint(path, p, previous_cpu_seconds);
                    loaded = true;
                    std::size_t finished = 0, started = 0;
                    for (const auto& record : book) {
                        if (record && record->finished) ++finished;
                        else if (record) ++started;
                    }
                    note(fmt::format("resuming from {}: {} realizations finished, {} under way", path, finished,
                                     started));
                    break;
                } catch (const h5::Error& error) {
                    note(fmt::format("warning: {} cannot be read ({}); trying the older generation", path,
                                     error.what()));
                } catch (const OtherSimulator& other) {
                    note(fmt::format("warning: {}; starting from t = 0", other.what()));
                    break;
                }
            }
            if (!loaded) book.assign(realizations, std::nullopt);
        }
    }

    std::mutex mutex;
    std::condition_variable finished_one;
    std::vector<RealizationProgress> facts(realizations);
    std::atomic<std::size_t> next{0};
    std::exception_ptr failure;
    std::size_t running_workers = 0;
    std::atomic<bool> stopped{false};
    auto last_write = std::chrono::steady_clock::now();

    // Under the lock: writes the book whole (every realization's latest record).
    auto write_book = [&] {
        write_checkpoint(options.checkpoint, p, book, previous_cpu_seconds + process_cpu_seconds() - cpu_start);
        last_write = std::chrono::steady_clock::now();
    };

    auto work = [&](std::size_t r) {
        RealizationRecord record;
        {
            std::lock_guard lock(mutex);
            if (book[r]) record = *book[r];
        }
        if (record.finished) {
            std::lock_guard lock(mutex);
            facts[r] = {RealizationProgress::State::finished, record.end_time, record.counts.collisions()};
            return;
        }
        {
            std::lock_guard lock(mutex);
            facts[r] = {RealizationProgress::State::running, record.samples_done > 0 ? result.time[static_cast<std::size_t>(record.samples_done - 1)] : 0.0,
                        record.counts.collisions()};
        }
        std::optional<HardSphereEngine> engine;
        if (record.has_engine) {
            engine.emplace(record.engine, p.collision, p.collapse_speed);
        } else {
            const double start_cpu = thread_cpu_seconds();
            const SphereState start = make_start(p, p.first_realization + static_cast<std::int64_t>(r));
            record.start_seconds = thread_cpu_seconds() - start_cpu;
            engine.emplace(start, p.collision, p.collapse_speed);
        }
        // One row a histogram or snapshot time (a checkpoint holds those taken).
        record.histogram_rows.resize(histogram_times.size());
        record.density.resize(snapshot_times.size());
        record.velocity_field.resize(snapshot_times.size());
        record.positions.resize(snapshot_times.size());
        record.velocities.resize(snapshot_times.size());
        auto deposit = [&](bool with_engine) {
            record.counts = engine->counts();
            record.has_engine = with_engine;
            if (with_engine) record.engine = engine->save();
            book[r] = record;
            record.engine = {};
        };
        for (auto k = static_cast<std::size_t>(record.samples_done); k < samples; ++k) {
            const double t = result.time[k];
            if (!engine->advance_to(t, options.stop)) {
                stopped = true;
                std::lock_guard lock(mutex);
                deposit(true);
                return;
            }
            if (engine->status() == EngineStatus::collapsed) {
                record.status = "collapsed";
                record.end_time = engine->time();
                break;
            }
            const std::vector<double> v = engine->velocities();
            const double temperature_now = temperature(v, d);
            record.temperature.push_back(temperature_now);
            record.collisions_per_particle.push_back(2.0 * static_cast<double>(engine->counts().collisions()) /
                                                     static_cast<double>(p.particles));
            record.velocity_kurtosis.push_back(velocity_kurtosis(v, d));
            const auto h = static_cast<std::size_t>(std::find(histogram_times.begin(), histogram_times.end(), t) -
                                                    histogram_times.begin());
            if (h < histogram_times.size()) {
                auto& row = record.histogram_rows[h];
                row.assign(bins + 1, 0.0);
                const auto mean = mean_velocity(v, d);
                const double scale = 1.0 / std::sqrt(temperature_now);
                for (std::size_t i = 0; i < v.size(); ++i) {
                    const double z = (v[i] - mean[i % static_cast<std::size_t>(d)]) * scale;
                    const double position = (z + p.histogram_range) / (2.0 * p.histogram_range) * static_cast<double>(bins);
                    if (position >= 0.0 && position < static_cast<double>(bins))
                        row[static_cast<std::size_t>(position)] += 1.0;
                    else
                        row[bins] += 1.0;
                }
            }
            const auto s = static_cast<std::size_t>(std::find(snapshot_times.begin(), snapshot_times.end(), t) -
                                                    snapshot_times.begin());
            if (s < snapshot_times.size()) {
                const SphereState state = engine->state();
                record.density[s].assign(field_cells, 0.0);
                record.velocity_field[s].assign(field_cells * static_cast<std::size_t>(d), 0.0);
                coarse_fields(state, p.field_cells, record.density[s].data(), record.velocity_field[s].data());
                if (r == 0) {
                    record.positions[s] = state.positions;
                    record.velocities[s] = state.velocities;
                }
            }
            record.samples_done = static_cast<std::int64_t>(k + 1);
            std::lock_guard lock(mutex);
            facts[r] = {RealizationProgress::State::running, t, engine->counts().collisions()};
            if (!options.checkpoint.empty() &&
                std::chrono::duration<double>(std::chrono::steady_clock::now() - last_write).count() >=
                    options.checkpoint_interval_seconds) {
                deposit(true);
                write_book();
            }
        }
        std::lock_guard lock(mutex);
        if (record.status == "complete") record.end_time = p.t_max;
        record.finished = true;
        deposit(false);
        facts[r] = {RealizationProgress::State::finished, record.end_time, engine->counts().collisions()};
    };

    const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t thread_count =
        std::min<std::size_t>(realizations, p.threads > 0 ? static_cast<std::size_t>(p.threads) : hardware);
    std::vector<std::thread> threads;
    running_workers = thread_count;
    for (std::size_t w = 0; w < thread_count; ++w)
        threads.emplace_back([&] {
            for (std::size_t r = next++; r < realizations; r = next++) {
                if (stopped) break;
                try {
                    work(r);
                } catch (...) {
                    std::lock_guard lock(mutex);
                    if (!failure) failure = std::current_exception();
                    next = realizations;
                }
            }
            std::lock_guard lock(mutex);
            --running_workers;
            finished_one.notify_all();
        });
    {
        std::unique_lock lock(mutex);
        while (running_workers > 0) {
            finished_one.wait_for(lock, std::chrono::seconds(1));
            if (!progress) continue;
            Progress report;
            report.elapsed_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
            report.t_max = p.t_max;
            report.realizations = p.realizations;
            report.realization = facts;
            for (const auto& fact : facts) {
                report.collisions_this_process += fact.collisions;
                if (fact.state == RealizationProgress::State::finished) ++report.realizations_done;
            }
            report.collisions_per_second =
                report.elapsed_seconds > 0.0 ? static_cast<double>(report.collisions_this_process) / report.elapsed_seconds : 0.0;
            lock.unlock();
            progress(report);
            lock.lock();
        }
    }
    for (auto& thread : threads) thread.join();
    if (failure) std::rethrow_exception(failure);
    if (!options.checkpoint.empty() && (stopped || options.checkpoint_when_done)) {
        write_book();
        if (!stopped) note(fmt::format("checkpoint: every realization finished, kept in {} until the output is written",
                                       options.checkpoint));
    }
    result.interrupted = stopped;

    // The result, from the book, in realization order.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    result.temperature.assign(realizations * samples, nan);
    result.collisions_per_particle.assign(realizations * samples, nan);
    result.velocity_kurtosis.assign(realizations * samples, nan);
    result.status.assign(realizations, "complete");
    result.end_time.assign(realizations, nan);
    result.snapshots.resize(snapshot_times.size());
    for (std::size_t s = 0; s < snapshot_times.size(); ++s) {
        result.snapshots[s].time = snapshot_times[s];
        result.snapshots[s].density.assign(realizations * field_cells, nan);
        result.snapshots[s].velocity_field.assign(realizations * field_cells * static_cast<std::size_t>(d), nan);
    }
    for (std::size_t h = 0; h < histogram_times.size(); ++h) {
        SphereHistogram histogram;
        histogram.time = histogram_times[h];
        histogram.counts.assign(bins, 0.0);
        result.histograms.push_back(std::move(histogram));
    }
    for (std::size_t r = 0; r < realizations; ++r) {
        if (!book[r]) continue;
        const RealizationRecord& record = *book[r];
        std::copy(record.temperature.begin(), record.temperature.end(), result.temperature.begin() + static_cast<std::ptrdiff_t>(r * samples));
        std::copy(record.collisions_per_particle.begin(), record.collisions_per_particle.end(),
                  result.collisions_per_particle.begin() + static_cast<std::ptrdiff_t>(r * samples));
        std::copy(record.velocity_kurtosis.begin(), record.velocity_kurtosis.end(),
                  result.velocity_kurtosis.begin() + static_cast<std::ptrdiff_t>(r * samples));
        result.status[r] = record.status;
        result.end_time[r] = record.end_time;
        for (std::size_t h = 0; h < histogram_times.size() && h < record.histogram_rows.size(); ++h) {
            const auto& row = record.histogram_rows[h];
            if (row.empty()) continue;
            for (std::size_t b = 0; b < bins; ++b) result.histograms[h].counts[b] += row[b];
            result.histograms[h].outside += row[bins];
        }
        for (std::size_t s = 0; s < snapshot_times.size() && s < record.density.size(); ++s) {
            if (record.density[s].empty()) continue;
            std::copy(record.density[s].begin(), record.density[s].end(),
                      result.snapshots[s].density.begin() + static_cast<std::ptrdiff_t>(r * field_cells));
            std::copy(record.velocity_field[s].begin(), record.velocity_field[s].end(),
                      result.snapshots[s].velocity_field.begin() +
                          static_cast<std::ptrdiff_t>(r * field_cells * static_cast<std::size_t>(d)));
            if (r == 0) {
                result.snapshots[s].positions = record.positions[s];
                result.snapshots[s].velocities = record.velocities[s];
            }
        }
        result.counts.inelastic += record.counts.inelastic;
        result.counts.elastic += record.counts.elastic;
        result.counts.cell_crossings += record.counts.cell_crossings;
        result.counts.stale_events += record.counts.stale_events;
        result.start_seconds += record.start_seconds;
    }
    result.cpu_seconds = previous_cpu_seconds + process_cpu_seconds() - cpu_start;
    result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    return result;
}

}  // namespace shockgas::spheres
