#include "obscura/io/vdb_stream_reader.h"

#include <fmt/format.h>

namespace obscura::vdb_format {

VdbStreamReader::VdbStreamReader(const std::filesystem::path& path, std::uint64_t size)
    : in_(path, std::ios::binary), file_(path.string()), size_(size) {
  if (!in_) throw InputError(file_, "", "cannot open the OpenVDB file");
}

void VdbStreamReader::need(std::uint64_t n, const std::string& part) const {
  if (n > size_ - pos_)
    throw InputError(file_, part,
                     fmt::format("needs {} bytes from byte {} but the file ends at byte {}: "
                                 "the OpenVDB file is truncated or corrupt",
                                 n, pos_, size_));
}

void VdbStreamReader::read_into(void* dst, std::uint64_t n, const std::string& part) {
  need(n, part);
  in_.read(static_cast<char*>(dst), static_cast<std::streamsize>(n));
  if (!in_) throw InputError(file_, part, "cannot read the OpenVDB file");
  pos_ += n;
}

std::string VdbStreamReader::string(const std::string& part) {
  const auto n = read<std::uint32_t>(part);
  need(n, part);
  std::string s(n, '\0');
  read_into(s.data(), n, part);
  return s;
}

std::string VdbStreamReader::name(const std::string& part) {
  std::string s = string(part);
  if (s.size() > 4096) throw error(part, "a name longer than 4096 bytes: the file is corrupt");
  return s;
}

std::vector<unsigned char> VdbStreamReader::bytes(std::uint64_t n, const std::string& part) {
  need(n, part);
  std::vector<unsigned char> v(n);
  read_into(v.data(), n, part);
  return v;
}

void VdbStreamReader::seek(std::uint64_t to, const std::string& part) {
  if (to < pos_)
    throw InputError(file_, part,
                     fmt::format("points back to byte {} from byte {}: the OpenVDB file is "
                                 "corrupt",
                                 to, pos_));
  if (to > size_)
    throw InputError(file_, part,
                     fmt::format("points to byte {} but the file ends at byte {}: the OpenVDB "
                                 "file is truncated or corrupt",
                                 to, size_));
  pos_ = to;
  in_.seekg(static_cast<std::streamoff>(to));
}

}  // namespace obscura::vdb_format
