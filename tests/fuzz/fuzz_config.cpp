// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer harness: shockgas-sim's parameter and config-file parsing.
//
// shockgas_sim.cpp is compiled into this harness with main renamed (see
// run_fuzz.sh). Each input is written to a temporary TOML/INI file and run as
//   shockgas-sim --config FILE -q -o /nonexistent/out.h5
// The output directory does not exist, so even a fully valid configuration
// stops at the writability check before any simulation: every input must end
// with an ordinary exit status (0 for --help, 2 for an input error), never a
// crash, sanitizer report or uncaught exception.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <unistd.h>

int shockgas_sim_main(int argc, char** argv);

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = "/tmp/shockgas_fuzz_config_" + std::to_string(::getpid()) + ".toml";
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (file == nullptr) return 0;
    std::fwrite(data, 1, size, file);
    std::fclose(file);
    std::vector<std::string> args = {"shockgas-sim", "--config", path, "-q", "-o", "/nonexistent_shockgas_dir/out.h5"};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const int status = shockgas_sim_main(static_cast<int>(args.size()), argv.data());
    // Exit statuses the CLI documents: 0 (help), 2 (input error). 1 is an
    // internal error: a finding.
    if (status != 0 && status != 2) {
        std::fprintf(stderr, "fuzz_config: unexpected exit status %d\n", status);
        std::abort();
    }
    std::remove(path.c_str());
    return 0;
}
