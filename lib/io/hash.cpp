#include "io/hash.hpp"

#include <openssl/evp.h>

#include <array>
#include <fstream>
#include <memory>

#include "core/errors.hpp"

namespace hm::io {
namespace {

struct DigestContext {
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx{EVP_MD_CTX_new(), &EVP_MD_CTX_free};
  // The OpenSSL calls must run in every build: their results are checked, never asserted.
  DigestContext() {
    if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1)
      throw InternalError("OpenSSL: SHA-256 initialisation failed");
  }
  void add(const void* data, std::size_t size) {
    if (EVP_DigestUpdate(ctx.get(), data, size) != 1)
      throw InternalError("OpenSSL: SHA-256 update failed");
  }
  std::string hex() {
    std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
    unsigned int length = 0;
    if (EVP_DigestFinal_ex(ctx.get(), digest.data(), &length) != 1)
      throw InternalError("OpenSSL: SHA-256 finalisation failed");
    static constexpr char digits[] = "0123456789abcdef";
    std::string out;
    for (unsigned int i = 0; i < length; ++i) {
      out += digits[digest[i] >> 4];
      out += digits[digest[i] & 15];
    }
    return out;
  }
};

}  // namespace

std::string sha256_file(const std::filesystem::path& path) {
  return sha256_file_from(path, 0);
}

std::string sha256_file_from(const std::filesystem::path& path, std::uint64_t offset) {
  std::ifstream in(path, std::ios::binary);
  if (!in) input_error("cannot read '{}' to hash it: no such file or no permission", path.string());
  in.seekg(static_cast<std::streamoff>(offset));
  DigestContext digest;
  std::array<char, 1 << 16> buffer{};
  while (in) {
    in.read(buffer.data(), buffer.size());
    digest.add(buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) input_error("read error while hashing '{}'", path.string());
  return digest.hex();
}

std::string sha256_text(std::string_view text) {
  DigestContext digest;
  digest.add(text.data(), text.size());
  return digest.hex();
}

}  // namespace hm::io
