#include "obscura/io/vdb_grid_check.h"

#include <fmt/format.h>
#include <openvdb/openvdb.h>

#include <array>
#include <bit>
#include <limits>
#include <set>
#include <vector>

#include "obscura/core/memory_limit.h"
#include "obscura/io/vdb_chunk_check.h"
#include "obscura/io/vdb_metadata_check.h"

namespace obscura::vdb_format {
namespace {

constexpr std::uint32_t kCompressZip = 0x1;
constexpr std::uint32_t kCompressActiveMask = 0x2;
constexpr std::uint32_t kCompressBlosc = 0x4;
constexpr std::string_view kHalfSuffix = "_HalfFloat";

using FloatRoot = openvdb::FloatTree::RootNodeType;
using FloatUpper = FloatRoot::ChildNodeType;   // 32^3 children
using FloatLower = FloatUpper::ChildNodeType;  // 16^3 children
using FloatLeaf = FloatLower::ChildNodeType;   // 8^3 voxels

// The bytes each linear map writes (math/Maps.h, read()): Vec3d and Mat4d
// members of 24 and 128 bytes.
std::uint64_t linear_map_bytes(const std::string& type) {
  if (type == "AffineMap" || type == "UnitaryMap") return 128;
  if (type == "ScaleMap" || type == "UniformScaleMap") return 5 * 24;
  if (type == "TranslationMap") return 24;
  if (type == "ScaleTranslateMap" || type == "UniformScaleTranslateMap") return 6 * 24;
  return 0;
}

// math::Transform::read: the map's type name, then the map.
void check_transform(VdbStreamReader& r, const std::string& part) {
  const std::string where = part + " transform";
  const std::string type = r.string(where);
  if (const std::uint64_t n = linear_map_bytes(type)) return r.skip(n, where);
  if (type == "NonlinearFrustumMap") {
    // Its box (two Vec3d), taper and depth, then a linear map.
    r.skip(48 + 8 + 8, where);
    const std::string second = r.string(where);
    if (const std::uint64_t n = linear_map_bytes(second)) return r.skip(n, where);
    throw r.error(where, fmt::format("a frustum over a '{}' map, which OpenVDB does not know",
                                     second.substr(0, 64)));
  }
  throw r.error(where, fmt::format("a '{}' map, which OpenVDB does not know", type.substr(0, 64)));
}

struct TreeCounts {
  std::uint64_t upper = 0, lower = 0, leaves = 0, tiles = 0;
};

class FloatTreeCheck {
 public:
  // `as_halves`: the values are stored as 16-bit halves (MetadataFacts).
  FloatTreeCheck(VdbStreamReader& r, const GridExtent& g, std::uint32_t compression, bool as_halves)
      : r_(r), g_(g), compression_(compression), half_(as_halves) {}

  TreeCounts topology() {
    const std::string part = g_.part + " topology";
    if (r_.read<std::int32_t>(part) != 1)
      throw r_.error(part, "a tree with other than one buffer: the file is corrupt");
    r_.skip(sizeof(float), part);  // background
    const auto tiles = r_.read<std::uint32_t>(part);
    const auto children = r_.read<std::uint32_t>(part);
    std::set<std::array<std::int32_t, 3>> origins;
    constexpr std::uint64_t kTileBytes = 3 * 4 + sizeof(float) + 1;
    r_.need(std::uint64_t{tiles} * kTileBytes, part);
    for (std::uint32_t i = 0; i < tiles; ++i) {
      root_origin(origins, part);
      r_.skip(sizeof(float) + 1, part);  // value, active
    }
    counts_.tiles = tiles;
    for (std::uint32_t i = 0; i < children; ++i) {
      root_origin(origins, part);
      internal_node(FloatUpper::LOG2DIM, part);
    }
    return counts_;
  }

  // Every leaf's value mask and values, in any order: all have one layout.
  void buffers() {
    const std::string part = g_.part + " data";
    for (std::uint64_t i = 0; i < counts_.leaves; ++i) {
      const std::vector<unsigned char> mask = r_.bytes(FloatLeaf::NUM_VOXELS / 8, part);
      compressed_values(FloatLeaf::NUM_VOXELS, count_on(mask), part);
    }
  }

 private:
  // Root children and tiles sit on the 4096-voxel lattice of the upper
  // nodes, each origin once: OpenVDB keys its table by the origin as read,
  // and a second child at the same origin would replace (and leak) the first.
  void root_origin(std::set<std::array<std::int32_t, 3>>& origins, const std::string& part) {
    std::array<std::int32_t, 3> o{};
    for (auto& c : o) c = r_.read<std::int32_t>(part);
    for (const auto c : o)
      if ((c & static_cast<std::int32_t>(FloatUpper::DIM - 1)) != 0)
        throw r_.error(part, fmt::format("a root entry at ({}, {}, {}), off the {}-voxel lattice "
                                         "of its nodes: the file is corrupt",
                                         o[0], o[1], o[2], static_cast<int>(FloatUpper::DIM)));
    if (!origins.insert(o).second)
      throw r_.error(part, fmt::format("two root entries at ({}, {}, {}): the file is corrupt",
                                       o[0], o[1], o[2]));
  }

  // InternalNode::readTopology: child mask, value mask, all values
  // compressed, then the children in mask order.
  void internal_node(int log2dim, const std::string& part) {
    const std::uint64_t values = std::uint64_t{1} << (3 * log2dim);
    const std::vector<unsigned char> child_mask = r_.bytes(values / 8, part);
    const std::vector<unsigned char> value_mask = r_.bytes(values / 8, part);
    compressed_values(values, count_on(value_mask), part);
    const std::uint64_t children = count_on(child_mask);
    if (log2dim == static_cast<int>(FloatUpper::LOG2DIM)) {
      ++counts_.upper;
      for (std::uint64_t i = 0; i < children; ++i)
        internal_node(static_cast<int>(FloatLower::LOG2DIM), part);
    } else {
      ++counts_.lower;
      counts_.leaves += children;
      r_.skip(children * (FloatLeaf::NUM_VOXELS / 8), part);  // leaf value masks
    }
  }

  // io::readCompressedValues (file format >= 222): a flag byte saying which
  // inactive values and selection mask follow, then the values, only the
  // active ones when the grid is mask-compressed.
  void compressed_values(std::uint64_t count, std::uint64_t active, const std::string& part) {
    const auto flag = r_.read<std::int8_t>(part);
    if (flag < 0 || flag > 6)
      throw r_.error(part, fmt::format("a node with value flag {} (0 to 6 expected): the file "
                                       "is corrupt",
                                       flag));
    enum : std::int8_t {
      kOneInactive = 2,
      kMask = 3,
      kMaskOneInactive = 4,
      kMaskTwoInactive = 5,
      kAllValues = 6
    };
    if (flag == kOneInactive || flag == kMaskOneInactive || flag == kMaskTwoInactive)
      r_.skip(sizeof(float), part);
    if (flag == kMaskTwoInactive) r_.skip(sizeof(float), part);
    if (flag == kMask || flag == kMaskOneInactive || flag == kMaskTwoInactive)
      r_.skip(count / 8, part);  // selection mask
    const std::uint64_t stored =
        (compression_ & kCompressActiveMask) && flag != kAllValues ? active : count;
    if (half_ && stored == 0) return;  // HalfReader reads nothing then
    const std::uint64_t bytes = stored * (half_ ? 2 : sizeof(float));
    if (compression_ & (kCompressBlosc | kCompressZip))
      chunk(bytes, part);
    else
      r_.skip(bytes, part);
  }

  // bloscFromStream / unzipFromStream: an int64 size, negative for raw bytes.
  void chunk(std::uint64_t expected, const std::string& part) {
    const auto n = r_.read<std::int64_t>(part);
    if (n <= 0) {
      if (n == std::numeric_limits<std::int64_t>::min() ||
          static_cast<std::uint64_t>(-n) != expected)
        throw r_.error(part, fmt::format("a raw chunk whose size field is {} where -{} is "
                                         "expected: the file is corrupt",
                                         n, expected));
      return r_.skip(expected, part);
    }
    if (static_cast<std::uint64_t>(n) > g_.end_pos - std::min(g_.end_pos, r_.position()))
      throw r_.error(part, fmt::format("a compressed chunk of {} bytes at byte {} runs past the "
                                       "grid's end at byte {}: the file is corrupt",
                                       n, r_.position(), g_.end_pos));
    const std::vector<unsigned char> c = r_.bytes(static_cast<std::uint64_t>(n), part);
    const auto problem = (compression_ & kCompressBlosc)
                             ? blosc_chunk_problem(c.data(), c.size(), expected)
                             : zip_chunk_problem(c.data(), c.size(), expected);
    if (problem) throw r_.error(part, *problem + ": the file is corrupt");
  }

  static std::uint64_t count_on(const std::vector<unsigned char>& mask) {
    std::uint64_t n = 0;
    for (const unsigned char b : mask) n += static_cast<std::uint64_t>(std::popcount(b));
    return n;
  }

  VdbStreamReader& r_;
  const GridExtent& g_;
  std::uint32_t compression_;
  bool half_;
  TreeCounts counts_;
};

bool is_float_tree(const std::string& type) {
  const std::string plain = openvdb::FloatTree::treeType();
  return type == plain || type == plain + std::string(kHalfSuffix);
}

}  // namespace

void check_grid_data(VdbStreamReader& r, const GridExtent& g) {
  if (r.position() != g.grid_pos)
    throw r.error(g.part, fmt::format("its data is said to start at byte {}, not after its "
                                      "descriptor at byte {}: the file is corrupt",
                                      g.grid_pos, r.position()));
  const auto compression = r.read<std::uint32_t>(g.part + " compression");
  if (compression > (kCompressZip | kCompressActiveMask | kCompressBlosc))
    throw r.error(g.part + " compression",
                  fmt::format("unknown compression flags {:#x}: the file is corrupt", compression));
  const MetadataFacts metadata = check_metadata_block(r, g.part + " metadata");
  check_transform(r, g.part);
  if (r.position() > g.end_pos)
    throw r.error(g.part, "its metadata runs past its end: the file is corrupt");
  if (g.instance || !is_float_tree(g.type)) return r.seek(g.end_pos, g.part);

  FloatTreeCheck tree(r, g, compression, metadata.saved_as_half);
  const TreeCounts n = tree.topology();
  if (r.position() != g.block_pos)
    throw r.error(g.part, fmt::format("its tree ends at byte {}, not where its data is said to "
                                      "start (byte {}): the file is corrupt",
                                      r.position(), g.block_pos));
  // What OpenVDB will allocate for the tree, before it does.
  const std::uint64_t tree_bytes =
      n.upper * sizeof(FloatUpper) + n.lower * sizeof(FloatLower) +
      n.leaves * (sizeof(FloatLeaf) + FloatLeaf::NUM_VOXELS * sizeof(float)) + n.tiles * 64;
  check_memory(tree_bytes, r.file(), g.part, "its OpenVDB tree");
  tree.buffers();
  if (r.position() != g.end_pos)
    throw r.error(g.part, fmt::format("its data ends at byte {}, not at byte {} as its descriptor "
                                      "says: the file is corrupt",
                                      r.position(), g.end_pos));
}

}  // namespace obscura::vdb_format
