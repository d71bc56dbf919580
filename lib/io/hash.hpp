#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace hm::io {

/// SHA-256 of a file's content, lowercase hex. Throws InputError naming the file if unreadable.
std::string sha256_file(const std::filesystem::path& path);
/// SHA-256 of a file's content from byte `offset` on, lowercase hex; as sha256_file.
std::string sha256_file_from(const std::filesystem::path& path, std::uint64_t offset);
/// SHA-256 of a byte string, lowercase hex.
std::string sha256_text(std::string_view text);

}  // namespace hm::io
