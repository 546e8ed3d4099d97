#pragma once
// Reads an OpenVDB file as bytes, for the checks that walk it before
// OpenVDB does (vdb_stream_check.h): every read is first checked against the
// file's length, so that a length read from the file is never trusted.
// Internal to io/.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "obscura/core/error.h"

namespace obscura::vdb_format {

class VdbStreamReader {
 public:
  VdbStreamReader(const std::filesystem::path& path, std::uint64_t size);

  std::uint64_t position() const { return pos_; }
  std::uint64_t size() const { return size_; }
  const std::string& file() const { return file_; }

  // Throws unless `n` more bytes are in the file; `part` names what is being
  // read (a grid, a metadata entry), for the message.
  void need(std::uint64_t n, const std::string& part) const;

  template <class T>
  T read(const std::string& part) {
    T v{};
    read_into(&v, sizeof(T), part);
    return v;
  }
  // A uint32 length and that many bytes, as OpenVDB writes names.
  std::string string(const std::string& part);
  // The same for a name (a grid's, a type's, a metadata entry's): names are
  // short, and one longer than 4096 bytes is garbage, refused.
  std::string name(const std::string& part);
  std::vector<unsigned char> bytes(std::uint64_t n, const std::string& part);
  void skip(std::uint64_t n, const std::string& part) { seek(pos_ + n, part); }
  // Only forward, and not past the end of the file.
  void seek(std::uint64_t to, const std::string& part);

  InputError error(const std::string& part, const std::string& what) const {
    return InputError(file_, part, what);
  }

 private:
  void read_into(void* dst, std::uint64_t n, const std::string& part);

  std::ifstream in_;
  std::string file_;
  std::uint64_t size_;
  std::uint64_t pos_ = 0;
};

}  // namespace obscura::vdb_format
