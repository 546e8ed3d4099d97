#include "obscura/io/vdb_stream_check.h"

#include <fmt/format.h>
#include <openvdb/version.h>

#include <cctype>
#include <cstdint>
#include <string>
#include <vector>

#include "obscura/core/error.h"
#include "obscura/io/vdb_grid_check.h"
#include "obscura/io/vdb_keyframe_layout.h"
#include "obscura/io/vdb_metadata_check.h"
#include "obscura/io/vdb_stream_reader.h"

namespace obscura::vdb_format {
namespace {

// The layout OpenVDB writes (io/Archive.cc, io/File.cc, GridDescriptor.cc):
// int64 magic, uint32 file version, uint32 library major and minor,
// char "has grid offsets", 36 bytes of UUID; the file metadata; int32 grid
// count; per grid a name, a type and an instance-parent string, int64 grid,
// block and end offsets, then its data up to the end offset
// (vdb_grid_check.h). A string is uint32 length + bytes.
constexpr std::int64_t kMagic = 0x56444220;
// OpenVDB 3.0 (2014) and later write version 222 or above; the older
// layouts (no per-node value flags) are not walked, so they are refused.
constexpr std::uint32_t kNodeMaskCompression = 222;
// What this OpenVDB writes; it only warns about newer files and reads on, in
// a layout it does not know.
constexpr std::uint32_t kNewestVersion = openvdb::OPENVDB_FILE_VERSION;

// OpenVDB 10 reads the file's UUID with boost's formatted extraction
// (`is >> uuid`), which stops at the first character out of place, so a
// mutated UUID shifts everything OpenVDB reads after it (a metadata name of
// 1.6 GB) away from where this walk reads. The walk therefore holds the UUID
// to the form OpenVDB writes: 8-4-4-4-12 hexadecimal digits.
void check_uuid(VdbStreamReader& r) {
  const std::vector<unsigned char> uuid = r.bytes(36, "header");
  for (std::size_t i = 0; i < uuid.size(); ++i) {
    const bool hyphen = i == 8 || i == 13 || i == 18 || i == 23;
    if (hyphen ? uuid[i] != '-' : std::isxdigit(uuid[i]) == 0)
      throw r.error("header",
                    "its UUID is not 36 characters of hexadecimal digits and hyphens: "
                    "the OpenVDB file is corrupt");
  }
}

}  // namespace

void check_vdb_stream(const std::filesystem::path& path) {
  ensure_openvdb_initialized();  // the metadata check asks OpenVDB's type registry
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path.string(), "", "cannot read the OpenVDB file's size");
  VdbStreamReader r(path, size);

  if (r.read<std::int64_t>("header") != kMagic)
    throw r.error("header", "not an OpenVDB file (no VDB magic number)");
  const auto version = r.read<std::uint32_t>("header");
  if (version < kNodeMaskCompression)
    throw r.error("header", fmt::format("OpenVDB file version {} is older than {} (OpenVDB 3.0), "
                                        "the oldest read; save it again with a newer OpenVDB",
                                        version, kNodeMaskCompression));
  if (version > kNewestVersion)
    throw r.error("header", fmt::format("OpenVDB file version {} is newer than {}, the newest this "
                                        "OpenVDB library reads",
                                        version, kNewestVersion));
  r.skip(2 * sizeof(std::uint32_t), "header");  // library version
  const bool has_offsets = r.read<char>("header") != 0;
  check_uuid(r);

  check_metadata_block(r, "file metadata");
  if (!has_offsets)
    throw r.error("header",
                  "a stream written without grid offsets, which obscura does not read; "
                  "write it with openvdb::io::File");

  const auto grid_count = r.read<std::int32_t>("grid descriptors");
  if (grid_count < 0)
    throw r.error("grid descriptors", "a negative grid count: the file is corrupt");
  for (std::int32_t i = 0; i < grid_count; ++i) {
    const std::string nth = fmt::format("grid descriptor {}", i);
    GridExtent g;
    const std::string name = r.name(nth);
    g.part = name.empty() ? nth : "grid " + name;
    g.type = r.name(g.part);
    g.instance = !r.name(g.part).empty();  // the instance parent
    const auto grid_pos = r.read<std::int64_t>(g.part);
    const auto block_pos = r.read<std::int64_t>(g.part);
    const auto end_pos = r.read<std::int64_t>(g.part);
    // An instance stores no tree, and OpenVDB leaves its block offset at 0.
    const bool no_blocks = g.instance && block_pos == 0;
    if (grid_pos < 0 || (!no_blocks && (block_pos < grid_pos || end_pos < block_pos)) ||
        end_pos < grid_pos)
      throw r.error(g.part, "its offsets are out of order: the file is corrupt");
    if (static_cast<std::uint64_t>(end_pos) > size)
      throw r.error(g.part, fmt::format("its data ends at byte {} but the file ends at byte {}: "
                                        "the OpenVDB file is truncated",
                                        end_pos, size));
    g.grid_pos = static_cast<std::uint64_t>(grid_pos);
    g.block_pos = static_cast<std::uint64_t>(block_pos);
    g.end_pos = static_cast<std::uint64_t>(end_pos);
    check_grid_data(r, g);
  }
}

}  // namespace obscura::vdb_format
