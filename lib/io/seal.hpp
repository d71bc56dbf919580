#pragma once
// The seal of an artefact: its first 512 bytes (an HDF5 user block, which HDF5 tools skip) hold
// "hydromodal artefact seal 1", the file's size and the SHA-256 of everything after the block,
// written when the artefact is committed. A reader checks the seal before HDF5 parses a byte, so
// a truncated, corrupted or edited file is refused with a clear message instead of reaching
// libhdf5's parser, which crashes on some corrupt files (HDF5 1.10.8, found by fuzz_artefact).
#include <cstdint>
#include <filesystem>

namespace hm::io {

/// Size of the user block that holds the seal [bytes] (HDF5 wants a power of 2, ≥ 512).
inline constexpr std::uint64_t seal_block_size = 512;

/// Writes the seal into the user block of the closed HDF5 file at `path` (created with a
/// seal_block_size user block).
void write_seal(const std::filesystem::path& path);

/// Checks the seal of the file at `path`; InputError naming the file when it is not HDF5, is
/// HDF5 without a seal (not written by a stage of this tool), or its size or content differ from
/// what was sealed.
void check_seal(const std::filesystem::path& path);

}  // namespace hm::io
