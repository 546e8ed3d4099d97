#include "obscura/io/vdb_metadata_check.h"

#include <fmt/format.h>
#include <openvdb/Grid.h>
#include <openvdb/Metadata.h>
#include <openvdb/io/DelayedLoadMetadata.h>

#include <cstdint>
#include <limits>

#include "obscura/io/vdb_chunk_check.h"

namespace obscura::vdb_format {
namespace {

// One array of DelayedLoadMetadata: a uint32 byte count, then a blosc chunk
// of that many bytes, or (count 0) `elements` raw values. Returns the bytes
// taken after the byte count.
std::uint64_t check_delayed_load_array(VdbStreamReader& r, std::uint32_t chunk_bytes,
                                       std::uint64_t array_bytes, const std::string& part) {
  if (chunk_bytes == 0) {
    r.skip(array_bytes, part);
    return array_bytes;
  }
  const std::vector<unsigned char> chunk = r.bytes(chunk_bytes, part);
  if (auto problem = blosc_chunk_problem(chunk.data(), chunk.size(), array_bytes, /*padded=*/true))
    throw r.error(part, *problem + ": the file is corrupt");
  return chunk_bytes;
}

// io::DelayedLoadMetadata::readValue: uint32 leaf count; the per-leaf mask
// bytes; the per-leaf compressed sizes (int64), or uint32 max for none.
// OpenVDB sizes both arrays by the count before it reads them, so the count
// is held to what the file could hold: every leaf takes at least its 64-byte
// value mask in the grid's data.
void check_delayed_load(VdbStreamReader& r, std::uint32_t value_bytes, const std::string& part) {
  if (value_bytes == 0) return;
  const std::uint64_t start = r.position();
  const auto leaves = r.read<std::uint32_t>(part);
  if (leaves > r.size() / 64)
    throw r.error(part, fmt::format("claims {} leaf nodes, more than a file of {} bytes holds: "
                                    "the file is corrupt",
                                    leaves, r.size()));
  check_delayed_load_array(r, r.read<std::uint32_t>(part), leaves, part);
  const auto size_bytes = r.read<std::uint32_t>(part);
  if (size_bytes != std::numeric_limits<std::uint32_t>::max())
    check_delayed_load_array(r, size_bytes, std::uint64_t{leaves} * 8, part);
  const std::uint64_t used = r.position() - start;
  if (used > value_bytes)
    throw r.error(part, fmt::format("holds {} bytes but says it has {}: the file is corrupt", used,
                                    value_bytes));
  r.skip(value_bytes - used, part);  // OpenVDB skips what it does not know
}

}  // namespace

MetadataFacts check_metadata_block(VdbStreamReader& r, const std::string& part) {
  MetadataFacts facts;
  const auto count = r.read<std::int32_t>(part);
  if (count < 0) throw r.error(part, "a negative entry count: the file is corrupt");
  for (std::int32_t i = 0; i < count; ++i) {
    const std::string nth = fmt::format("{} entry {}", part, i);
    const std::string name = r.name(nth);
    const std::string entry = name.empty() ? nth : fmt::format("{} '{}'", part, name);
    const std::string type = r.name(entry);
    const auto value_bytes = r.read<std::uint32_t>(entry);
    if (type == openvdb::io::DelayedLoadMetadata::staticTypeName()) {
      check_delayed_load(r, value_bytes, entry);
      continue;
    }
    // A type OpenVDB knows reads its own size whatever the entry says
    // (TypedMetadata::readValue); strings and unknown types read the
    // entry's size.
    if (type != openvdb::StringMetadata::staticTypeName() &&
        openvdb::Metadata::isRegisteredType(type)) {
      const openvdb::Index32 expected = openvdb::Metadata::createMetadata(type)->size();
      if (value_bytes != expected)
        throw r.error(entry, fmt::format("a {} value of {} bytes where OpenVDB reads {}: the "
                                         "file is corrupt",
                                         type, value_bytes, expected));
    }
    const bool is_bool = type == openvdb::BoolMetadata::staticTypeName();
    const bool is_half_flag = name == openvdb::GridBase::META_SAVE_HALF_FLOAT;
    if (is_half_flag && !is_bool)
      throw r.error(entry, fmt::format("has type {}, where OpenVDB writes a bool: the file is "
                                       "corrupt",
                                       type));
    if (is_bool) {
      const auto value = r.read<std::uint8_t>(entry);
      if (value > 1)
        throw r.error(entry, fmt::format("a bool of value {}: the file is corrupt", value));
      // A later entry of the same name replaces an earlier one (MetaMap::insertMeta).
      if (is_half_flag) facts.saved_as_half = value == 1;
      continue;
    }
    r.skip(value_bytes, entry);
  }
  return facts;
}

}  // namespace obscura::vdb_format
