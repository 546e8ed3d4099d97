#include "obscura/io/netcdf_classic_check.h"

#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "obscura/core/error.h"
#include "obscura/core/memory_limit.h"

namespace obscura::netcdf_cf {
namespace {

// Tags and type codes of the classic formats.
constexpr std::uint32_t kDimensionTag = 0x0A;
constexpr std::uint32_t kVariableTag = 0x0B;
constexpr std::uint32_t kAttributeTag = 0x0C;
constexpr std::uint64_t kStreamingRecords = 0xFFFFFFFFu;

// Bytes of one value of an external type (NC_BYTE = 1 ... NC_UINT64 = 11;
// the last five are CDF-5 only); empty for an unknown code.
std::optional<std::uint64_t> type_size(std::uint32_t type, bool cdf5) {
  static constexpr std::array<std::uint64_t, 12> kSize = {0, 1, 1, 2, 4, 4, 8, 1, 2, 4, 8, 8};
  if (type == 0 || type >= kSize.size() || (!cdf5 && type > 6)) return std::nullopt;
  return kSize[type];
}

std::uint64_t pad4(std::uint64_t n) { return (n + 3) / 4 * 4; }

// Big-endian reads from the whole header, each checked against the file.
class HeaderReader {
 public:
  HeaderReader(const std::filesystem::path& path, std::uint64_t file_size)
      : in_(path, std::ios::binary), file_(path.string()), size_(file_size) {
    if (!in_) throw InputError(file_, "", "cannot open the netCDF file");
  }

  const std::string& file() const { return file_; }
  std::uint64_t size() const { return size_; }
  std::uint64_t remaining() const { return size_ - pos_; }

  void need(std::uint64_t n, const std::string& part) const {
    if (n > remaining())
      throw InputError(file_, part,
                       fmt::format("the header needs {} bytes from byte {} but the file ends at "
                                   "byte {}: the netCDF file is truncated or corrupt",
                                   n, pos_, size_));
  }
  std::uint64_t uint(int bytes, const std::string& part) {
    need(static_cast<std::uint64_t>(bytes), part);
    std::array<unsigned char, 8> b{};
    in_.read(reinterpret_cast<char*>(b.data()), bytes);
    if (!in_) throw InputError(file_, part, "cannot read the netCDF file");
    pos_ += static_cast<std::uint64_t>(bytes);
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v = (v << 8) | b[static_cast<std::size_t>(i)];
    return v;
  }
  void skip(std::uint64_t n, const std::string& part) {
    need(n, part);
    pos_ += n;
    in_.seekg(static_cast<std::streamoff>(pos_));
  }
  std::string name(int count_bytes, const std::string& part) {
    const std::uint64_t n = uint(count_bytes, part);
    // NC_MAX_NAME is 256; a longer name is garbage, not a name.
    if (n > 256)
      throw InputError(
          file_, part,
          fmt::format("a name of {} bytes (at most 256): the netCDF file is corrupt", n));
    need(pad4(n), part);
    std::string s(n, '\0');
    in_.read(s.data(), static_cast<std::streamsize>(n));
    if (!in_) throw InputError(file_, part, "cannot read the netCDF file");
    skip_to(pos_ + pad4(n));
    return s;
  }
  InputError error(const std::string& part, const std::string& what) const {
    return InputError(file_, part, what);
  }

 private:
  void skip_to(std::uint64_t to) {
    pos_ = to;
    in_.seekg(static_cast<std::streamoff>(pos_));
  }
  std::ifstream in_;
  std::string file_;
  std::uint64_t size_;
  std::uint64_t pos_ = 0;
};

struct Layout {
  bool cdf5 = false;
  int count_bytes = 4;   // NON_NEG: 8 in CDF-5
  int offset_bytes = 4;  // OFFSET: 8 in CDF-2 and CDF-5
};

// A list header: ABSENT (two zeros) or the tag and the element count. The
// count is held to what the rest of the file could hold, `min_bytes` each,
// so that netCDF-C's arrays of that many elements stay within the file's
// size.
std::uint64_t list_count(HeaderReader& r, const Layout& l, std::uint32_t tag,
                         std::uint64_t min_bytes, const std::string& part) {
  const auto got = static_cast<std::uint32_t>(r.uint(4, part));
  const std::uint64_t n = r.uint(l.count_bytes, part);
  if (got == 0 && n == 0) return 0;
  if (got != tag)
    throw r.error(part, fmt::format("a list tag {:#x} where {:#x} is expected: the netCDF file "
                                    "is corrupt",
                                    got, tag));
  if (n > r.remaining() / min_bytes)
    throw r.error(part, fmt::format("claims {} entries, more than the {} bytes left in the file "
                                    "hold: the netCDF file is corrupt",
                                    n, r.remaining()));
  return n;
}

void attributes(HeaderReader& r, const Layout& l, const std::string& owner) {
  const std::string part = owner + " attributes";
  const std::uint64_t n = list_count(r, l, kAttributeTag, 12, part);
  for (std::uint64_t i = 0; i < n; ++i) {
    const std::string name = r.name(l.count_bytes, part);
    const std::string att = owner + ":" + name;
    const auto type = type_size(static_cast<std::uint32_t>(r.uint(4, att)), l.cdf5);
    if (!type) throw r.error(att, "an unknown value type: the netCDF file is corrupt");
    const std::uint64_t values = r.uint(l.count_bytes, att);
    if (values > r.remaining() / *type)
      throw r.error(att, fmt::format("claims {} values, more than the file holds: the netCDF "
                                     "file is corrupt",
                                     values));
    r.skip(pad4(values * *type), att);
  }
}

struct Variable {
  std::string name;
  bool is_record = false;   // its first dimension is the unlimited one
  std::uint64_t bytes = 0;  // per record for a record variable, else in all
  std::uint64_t begin = 0;
};

}  // namespace

void check_netcdf_classic_header(const std::filesystem::path& path) {
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path.string(), "", "cannot read the netCDF file's size");
  {
    std::ifstream in(path, std::ios::binary);
    std::array<char, 4> magic{};
    in.read(magic.data(), 4);
    if (!in || magic[0] != 'C' || magic[1] != 'D' || magic[2] != 'F') return;  // not classic
  }
  HeaderReader r(path, size);
  r.skip(3, "header");
  const auto version = r.uint(1, "header");
  if (version != 1 && version != 2 && version != 5)
    throw r.error("header",
                  fmt::format("classic netCDF version byte {} (1, 2 or 5 expected)", version));
  Layout l;
  l.cdf5 = version == 5;
  l.count_bytes = l.cdf5 ? 8 : 4;
  l.offset_bytes = version == 1 ? 4 : 8;

  const std::uint64_t records = r.uint(l.count_bytes, "numrecs");
  const std::uint64_t streaming = l.cdf5 ? ~std::uint64_t{0} : kStreamingRecords;

  // Dimensions: a name and a length each (0 for the record dimension).
  const std::uint64_t dim_count =
      list_count(r, l, kDimensionTag, 4 + static_cast<std::uint64_t>(l.count_bytes), "dimensions");
  std::vector<std::uint64_t> dim_len(dim_count);
  std::optional<std::uint64_t> record_dim;
  for (std::uint64_t d = 0; d < dim_count; ++d) {
    const std::string name = r.name(l.count_bytes, "dimensions");
    dim_len[d] = r.uint(l.count_bytes, "dimension " + name);
    if (dim_len[d] == 0) {
      if (record_dim) throw r.error("dimension " + name, "a second unlimited dimension");
      record_dim = d;
    }
  }
  attributes(r, l, "global");

  const std::uint64_t var_count = list_count(r, l, kVariableTag, 24, "variables");
  std::vector<Variable> vars(var_count);
  // The records' stride: the sum of every record variable's bytes per
  // record, each padded to 4 bytes unless there is only one.
  std::uint64_t padded_sum = 0, record_vars = 0, one_record_bytes = 0;
  for (Variable& v : vars) {
    v.name = r.name(l.count_bytes, "variables");
    const std::string part = "variable " + v.name;
    const std::uint64_t rank = r.uint(l.count_bytes, part);
    if (rank > r.remaining() / static_cast<std::uint64_t>(l.count_bytes))
      throw r.error(part, fmt::format("claims {} dimensions: the netCDF file is corrupt", rank));
    std::vector<std::uint64_t> lengths;
    for (std::uint64_t k = 0; k < rank; ++k) {
      const std::uint64_t id = r.uint(l.count_bytes, part);
      if (id >= dim_count)
        throw r.error(part,
                      fmt::format("dimension id {} but the file has {} dimensions", id, dim_count));
      if (record_dim && id == *record_dim) {
        if (k > 0) throw r.error(part, "the unlimited dimension is not its first");
        v.is_record = true;
      } else {
        lengths.push_back(dim_len[id]);
      }
    }
    attributes(r, l, v.name);
    const auto type = type_size(static_cast<std::uint32_t>(r.uint(4, part)), l.cdf5);
    if (!type) throw r.error(part, "an unknown value type: the netCDF file is corrupt");
    v.bytes = *type;
    for (const std::uint64_t n : lengths) {
      const auto p = checked_product({v.bytes, n});
      if (!p) throw r.error(part, "its size overflows 64 bits");
      v.bytes = *p;
    }
    r.uint(l.cdf5 ? 8 : 4, part);  // vsize: recomputed above, as netCDF-C does
    v.begin = r.uint(l.offset_bytes, part);
    if (v.is_record) {
      padded_sum += pad4(v.bytes);
      one_record_bytes = v.bytes;
      ++record_vars;
    }
  }
  const std::uint64_t record_stride = record_vars == 1 ? one_record_bytes : padded_sum;

  // Every variable's data within the file.
  for (const Variable& v : vars) {
    // Overflow-checked: a corrupt header's offsets and sizes may pass 64 bits.
    std::uint64_t end = 0, span = 0;
    bool overflow = __builtin_add_overflow(v.begin, v.bytes, &end);
    if (v.is_record) {
      if (records == 0 || records == streaming) continue;  // no record to read
      overflow = __builtin_mul_overflow(records - 1, record_stride, &span) ||
                 __builtin_add_overflow(end, span, &end) || overflow;
    }
    if (overflow || end > size)
      throw r.error("variable " + v.name,
                    fmt::format("its data ends past the end of the file ({} bytes): the netCDF "
                                "file is truncated or corrupt",
                                size));
  }
}

}  // namespace obscura::netcdf_cf
