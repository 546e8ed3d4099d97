#pragma once
// A file's bytes, read and written whole, for tests that corrupt files a
// byte at a time.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

namespace obscura::testing {

using Bytes = std::vector<char>;

inline Bytes read_file_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), {});
}

inline void write_file_bytes(const std::filesystem::path& p, const Bytes& b) {
  std::ofstream(p, std::ios::binary).write(b.data(), static_cast<std::streamsize>(b.size()));
}

}  // namespace obscura::testing
