// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/io/checksum.hpp"

#include <array>
#include <fstream>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>
#include <openssl/evp.h>

#include "shockgas/model/parameters.hpp"

namespace shockgas {

namespace {

// SHA-256 (FIPS 180-4) by OpenSSL's EVP interface: a well-kept, audited
// implementation rather than our own.
class Sha256 {
public:
    Sha256() : context_(EVP_MD_CTX_new(), &EVP_MD_CTX_free) {
        if (!context_ || EVP_DigestInit_ex(context_.get(), EVP_sha256(), nullptr) != 1)
            throw std::runtime_error("OpenSSL could not start a SHA-256 digest");
    }
    void add(const char* data, std::size_t size) {
        if (size > 0 && EVP_DigestUpdate(context_.get(), data, size) != 1)
            throw std::runtime_error("OpenSSL SHA-256 update failed");
    }
    std::string finish() {
        std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
        unsigned int size = 0;
        if (EVP_DigestFinal_ex(context_.get(), digest.data(), &size) != 1)
            throw std::runtime_error("OpenSSL SHA-256 finish failed");
        std::string hex;
        for (unsigned int k = 0; k < size; ++k) hex += fmt::format("{:02x}", digest[k]);
        return hex;
    }

private:
    std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> context_;
};

}  // namespace

std::string sha256_hex(const std::string& bytes) {
    Sha256 hash;
    hash.add(bytes.data(), bytes.size());
    return hash.finish();
}

std::string file_sha256(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(fmt::format("cannot read '{}' to checksum it", path));
    Sha256 hash;
    std::string chunk(1 << 20, '\0');
    while (in) {
        in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
        hash.add(chunk.data(), static_cast<std::size_t>(in.gcount()));
    }
    return hash.finish();
}

}  // namespace shockgas
