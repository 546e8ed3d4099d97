#include "obscura/io/vdb_stream_check.h"

#include <fmt/format.h>

#include <cstdint>
#include <fstream>
#include <string>

#include "obscura/core/error.h"

namespace obscura::vdb_format {
namespace {

// The layout OpenVDB writes (io/Archive.cc, io/File.cc, GridDescriptor.cc):
// int64 magic, uint32 file version, uint32 library major and minor (>= 211),
// char "has grid offsets" (>= 212), uint32 compression (220, 221), 36 bytes of
// UUID (>= 218); the file metadata (int32 count; per entry a name and a type
// string, uint32 size, the value); int32 grid count; per grid a name, a type
// and (>= 216) an instance-parent string, int64 grid, block and end offsets,
// then its data up to the end offset. A string is uint32 length + bytes.
constexpr std::int64_t kMagic = 0x56444220;
constexpr std::uint32_t kGridInstancing = 216;
constexpr std::uint32_t kBoostUuid = 218;
constexpr std::uint32_t kSelectiveCompression = 220;
constexpr std::uint32_t kNodeMaskCompression = 222;

class BoundedReader {
 public:
  BoundedReader(const std::filesystem::path& path, std::uint64_t size)
      : in_(path, std::ios::binary), file_(path.string()), size_(size) {
    if (!in_) throw InputError(file_, "", "cannot open the OpenVDB file");
  }

  std::uint64_t position() const { return pos_; }
  std::uint64_t size() const { return size_; }

  // `part` names what is being read, for the message.
  void need(std::uint64_t n, const std::string& part) const {
    if (n > size_ - pos_)
      throw InputError(file_, part,
                       fmt::format("needs {} bytes from byte {} but the file ends at byte {}: "
                                   "the OpenVDB file is truncated or corrupt",
                                   n, pos_, size_));
  }
  template <class T>
  T read(const std::string& part) {
    need(sizeof(T), part);
    T v{};
    in_.read(reinterpret_cast<char*>(&v), sizeof(T));
    if (!in_) throw InputError(file_, part, "cannot read the OpenVDB file");
    pos_ += sizeof(T);
    return v;
  }
  std::string string(const std::string& part) {
    const auto n = read<std::uint32_t>(part);
    need(n, part);
    std::string s(n, '\0');
    in_.read(s.data(), n);
    if (!in_) throw InputError(file_, part, "cannot read the OpenVDB file");
    pos_ += n;
    return s;
  }
  void skip(std::uint64_t n, const std::string& part) { seek(pos_ + n, part); }
  void seek(std::uint64_t to, const std::string& part) {
    if (to < pos_ || to > size_)
      throw InputError(file_, part,
                       fmt::format("points to byte {} but the file ends at byte {}: the OpenVDB "
                                   "file is truncated or corrupt",
                                   to, size_));
    pos_ = to;
    in_.seekg(static_cast<std::streamoff>(to));
  }
  InputError error(const std::string& part, const std::string& what) const {
    return InputError(file_, part, what);
  }

 private:
  std::ifstream in_;
  std::string file_;
  std::uint64_t size_;
  std::uint64_t pos_ = 0;
};

// Metadata names are short; anything longer is garbage, not a name.
std::string short_string(BoundedReader& r, const std::string& part) {
  std::string s = r.string(part);
  if (s.size() > 4096) throw r.error(part, "a name longer than 4096 bytes: the file is corrupt");
  return s;
}

}  // namespace

void check_vdb_stream(const std::filesystem::path& path) {
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path.string(), "", "cannot read the OpenVDB file's size");
  BoundedReader r(path, size);

  if (r.read<std::int64_t>("header") != kMagic)
    throw r.error("header", "not an OpenVDB file (no VDB magic number)");
  const auto version = r.read<std::uint32_t>("header");
  if (version < kSelectiveCompression)
    throw r.error("header", fmt::format("OpenVDB file version {} is older than {}, the oldest read",
                                        version, kSelectiveCompression));
  r.skip(2 * sizeof(std::uint32_t), "header");  // library version
  const bool has_offsets = r.read<char>("header") != 0;
  if (version < kNodeMaskCompression) r.skip(sizeof(std::uint32_t), "header");
  if (version >= kBoostUuid) r.skip(36, "header");

  const auto meta_count = r.read<std::int32_t>("file metadata");
  if (meta_count < 0) throw r.error("file metadata", "a negative entry count: the file is corrupt");
  for (std::int32_t i = 0; i < meta_count; ++i) {
    const std::string part = fmt::format("file metadata entry {}", i);
    const std::string name = short_string(r, part);
    const std::string entry = name.empty() ? part : "metadata " + name;
    short_string(r, entry);  // the type name
    r.skip(r.read<std::uint32_t>(entry), entry);
  }
  if (!has_offsets) return;  // a stream written without offsets: OpenVDB reads it in order

  const auto grid_count = r.read<std::int32_t>("grid descriptors");
  if (grid_count < 0)
    throw r.error("grid descriptors", "a negative grid count: the file is corrupt");
  for (std::int32_t i = 0; i < grid_count; ++i) {
    const std::string part = fmt::format("grid descriptor {}", i);
    const std::string name = short_string(r, part);
    const std::string grid = name.empty() ? part : "grid " + name;
    short_string(r, grid);  // the type
    if (version >= kGridInstancing) short_string(r, grid);
    const auto grid_pos = r.read<std::int64_t>(grid);
    const auto block_pos = r.read<std::int64_t>(grid);
    const auto end_pos = r.read<std::int64_t>(grid);
    if (grid_pos < 0 || block_pos < grid_pos || end_pos < block_pos)
      throw r.error(grid, "its offsets are out of order: the file is corrupt");
    if (static_cast<std::uint64_t>(end_pos) > size)
      throw r.error(grid, fmt::format("its data ends at byte {} but the file ends at byte {}: the "
                                      "OpenVDB file is truncated",
                                      end_pos, size));
    r.seek(static_cast<std::uint64_t>(end_pos), grid);
  }
}

}  // namespace obscura::vdb_format
