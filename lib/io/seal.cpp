#include "io/seal.hpp"

#include <hdf5.h>

#include <array>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "io/hash.hpp"

namespace hm::io {
namespace {

constexpr std::string_view magic = "hydromodal artefact seal 1\n";

struct Seal {
  std::uint64_t bytes = 0;
  std::string sha256;
};

std::string seal_text(const Seal& seal) {
  return fmt::format("{}bytes {}\nsha256 {}\n", magic, seal.bytes, seal.sha256);
}

/// The first seal_block_size bytes of the file (fewer for a shorter file).
std::string leading_block(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) input_error("'{}' cannot be read: no permission", path.string());
  std::string block(seal_block_size, '\0');
  in.read(block.data(), static_cast<std::streamsize>(block.size()));
  block.resize(static_cast<std::size_t>(in.gcount()));
  return block;
}

bool parse_seal(const std::string& block, Seal& seal) {
  if (block.compare(0, magic.size(), magic) != 0) return false;
  std::istringstream lines(block.substr(magic.size()));
  std::string bytes_key, sha_key;
  lines >> bytes_key >> seal.bytes >> sha_key >> seal.sha256;
  return lines && bytes_key == "bytes" && sha_key == "sha256" && seal.sha256.size() == 64;
}

/// Whether two digests are equal, compared without memcmp and without an early exit. A
/// coverage-guided fuzzer reads both sides of a memcmp or string compare and writes the computed
/// digest over the sealed one: libFuzzer forged seals that way within minutes and reached
/// libhdf5 1.10.8's parser with crafted files no disk or copy error can make, where HDF5 crashes
/// (H5A__close) and leaks, defects of the library that hydromodal cannot fix. Compared so, a
/// file reaches HDF5 only with a SHA-256 that matches its content.
bool same_digest(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  unsigned difference = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    difference |= static_cast<unsigned char>(a[i]) ^ static_cast<unsigned char>(b[i]);
  return difference == 0;
}

}  // namespace

void write_seal(const std::filesystem::path& path) {
  Seal seal;
  seal.bytes = std::filesystem::file_size(path);
  HM_ASSERT(seal.bytes >= seal_block_size, "an artefact has its user block");
  seal.sha256 = sha256_file_from(path, seal_block_size);
  std::string block = seal_text(seal);
  HM_ASSERT(block.size() < seal_block_size, "the seal fits its block");
  block.resize(seal_block_size, '\0');
  std::fstream out(path, std::ios::binary | std::ios::in | std::ios::out);
  out.write(block.data(), static_cast<std::streamsize>(block.size()));
  out.flush();
  if (!out) input_error("cannot write the seal of '{}'", path.string());
}

void check_seal(const std::filesystem::path& path) {
  Seal seal;
  if (!parse_seal(leading_block(path), seal)) {
    // H5Fis_hdf5 only looks for the superblock signature; it does not parse the file.
    if (H5Fis_hdf5(path.c_str()) <= 0)
      input_error(
          "'{}' is not an HDF5 file (or its header is corrupt); expected a hydromodal "
          "artefact written by an fsi-* stage",
          path.string());
    input_error(
        "'{}' is an HDF5 file without hydromodal's seal: it was not written by an fsi-* stage of "
        "this tool (or by one older than the seal). Rerun the stage that makes it",
        path.string());
  }
  const std::uint64_t bytes = std::filesystem::file_size(path);
  if (bytes != seal.bytes)
    input_error(
        "'{}' cannot be opened as HDF5: the file is truncated or corrupt ({} bytes, {} were "
        "written). Copy it again or rerun the stage that makes it",
        path.string(), bytes, seal.bytes);
  if (!same_digest(sha256_file_from(path, seal_block_size), seal.sha256))
    input_error(
        "'{}' is corrupt: its content does not match the SHA-256 sealed into it when it was "
        "written (a disk or copy error, or an edit outside hydromodal). Rerun the stage that "
        "makes it",
        path.string());
}

}  // namespace hm::io
