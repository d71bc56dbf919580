#pragma once
// Shared by the libFuzzer harnesses: the fuzzer's bytes as a file (the readers take paths), in a
// folder of this process, overwritten at every input. Private to tests/fuzz.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace hm::fuzz {

/// Writes `bytes` to <tmp>/hm_fuzz_<pid>/<name> and returns the path.
inline std::filesystem::path input_file(std::string_view bytes, const std::string& name) {
  static const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("hm_fuzz_" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  const std::filesystem::path path = folder / name;
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return path;
}

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

}  // namespace hm::fuzz
