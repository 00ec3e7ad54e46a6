// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer harness: the --init reader on arbitrary bytes.
//
// Mode byte 0 (even): the bytes are written as they are to a temporary .h5
// file and handed to shockgas::read_initial_condition, which must either
// return a valid initial condition or throw InputError; anything else
// (crash, sanitizer report, other exception) is a finding.
// Mode byte 1 (odd): the bytes describe a structurally valid HDF5 file with
// hostile contents (lengths, shapes, NaN/inf, unsorted or out-of-range
// positions, missing datasets or attribute), written through our own h5
// layer, so our validation layer is fuzzed even where HDF5 rejects the raw
// bytes early.
//
// The raw mode reaches bugs of libhdf5 1.10.8 itself on corrupt files (a
// heap-buffer-overflow in H5MM_strdup under H5Aexists, multi-GB mallocs in
// H5C_protect under H5Fopen) that no code of ours can guard, so CI's short
// run sets SHOCKGAS_FUZZ_STRUCTURED_ONLY and fuzzes our layer only; run
// without it by hand to fuzz through the library. Two raw inputs that did
// reach our reader's allocation are regression tests in tests/unit/test_io.cpp.
#include <algorithm>
#include <cstdlib>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <unistd.h>

#include "shockgas/io/initial_condition.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/model/parameters.hpp"
#include "shockgas/model/state.hpp"

namespace {

std::string temp_path() {
    return "/tmp/shockgas_fuzz_init_" + std::to_string(::getpid()) + ".h5";
}

// Consumes bytes from the input front to back.
struct Reader {
    const std::uint8_t* data;
    std::size_t size;
    std::size_t at = 0;
    std::uint8_t byte() { return at < size ? data[at++] : 0; }
    double number() {
        // Half the time a raw 64-bit pattern (NaN, inf, denormals), half a
        // small value in [-4, 12) that often lands near the valid range.
        if (byte() & 1) {
            std::uint64_t bits = 0;
            for (int k = 0; k < 8; ++k) bits = (bits << 8) | byte();
            double x;
            std::memcpy(&x, &bits, sizeof x);
            return x;
        }
        return static_cast<double>(byte()) / 16.0 - 4.0;
    }
    std::vector<double> numbers(std::size_t n) {
        std::vector<double> out(n);
        for (auto& x : out) x = number();
        return out;
    }
};

void write_structured(const std::string& path, Reader& in) {
    const std::uint8_t flags = in.byte();
    const std::size_t n = in.byte() % 12;
    const std::size_t n_velocity = (flags & 0x10) ? in.byte() % 12 : n;
    const std::size_t n_mass = (flags & 0x20) ? in.byte() % 12 : n;
    shockgas::h5::AtomicFile file(path + ".w");
    auto root = file.root();
    if (flags & 0x01) root.set_attribute("ring_length", in.number());
    if (flags & 0x40) root.set_attribute("ring_length", std::string("ten"));  // wrong type
    if (flags & 0x02) {
        auto position = in.numbers(n);
        if (flags & 0x80) std::sort(position.begin(), position.end());
        if (n > 0 && (flags & 0x80) && (n % 2 == 0))
            root.write("position", position, {static_cast<hsize_t>(n / 2), 2});  // two-dimensional
        else
            root.write("position", position);
    }
    if (flags & 0x04) root.write("velocity", in.numbers(n_velocity));
    if (flags & 0x08) root.write("mass", in.numbers(n_mass));
    if ((flags & 0x0C) == 0) root.write("velocity", std::vector<std::int64_t>(n, 1));  // integer dataset
    file.commit();
    std::rename((path + ".w").c_str(), path.c_str());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::string path = temp_path();
    Reader in{data + 1, size - 1};
    try {
        static const bool structured_only = std::getenv("SHOCKGAS_FUZZ_STRUCTURED_ONLY") != nullptr;
        if ((data[0] & 1) == 0 && !structured_only) {
            std::FILE* file = std::fopen(path.c_str(), "wb");
            if (file == nullptr) return 0;
            std::fwrite(data + 1, 1, size - 1, file);
            std::fclose(file);
        } else {
            write_structured(path, in);
        }
    } catch (const std::exception&) {
        return 0;  // our writer refused the structure: nothing to read
    }
    try {
        const auto initial = shockgas::read_initial_condition(path);
        shockgas::validate(initial);  // a returned condition must be valid
    } catch (const shockgas::InputError&) {
    }
    std::remove(path.c_str());
    return 0;
}
