// The walk over a whole OpenVDB file before OpenVDB reads it
// (io/vdb_stream_check.h). Truth is OpenVDB: every layout OpenVDB writes
// must pass the walk and read back, and the corruptions that made OpenVDB
// allocate what the file said are refused before it does.
#include "obscura/io/vdb_stream_check.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/math/Maps.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "obscura/core/error.h"
#include "obscura/core/memory_limit.h"
#include "support/file_bytes.h"
#include "support/input_error.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

namespace fs = std::filesystem;
using testing::Bytes;

template <class T>
T load(const Bytes& b, std::size_t at) {
  T v{};
  std::memcpy(&v, b.data() + at, sizeof(T));
  return v;
}

template <class T>
void store(Bytes& b, std::size_t at, T v) {
  std::memcpy(b.data() + at, &v, sizeof(T));
}

// A sparse grid with every kind of node: dense leaves with varied values,
// partly active leaves, constant tiles at the lower and upper internal
// levels and at the root.
openvdb::FloatGrid::Ptr sparse_grid(const std::string& name) {
  auto g = openvdb::FloatGrid::create(0.0f);
  g->setName(name);
  g->setTransform(openvdb::math::Transform::createLinearTransform(0.5));
  auto acc = g->getAccessor();
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 12; ++j)
      for (int k = 0; k < 9; ++k)
        if ((i + j + k) % 3 != 0) acc.setValue({i, j, k}, 0.25f * static_cast<float>(i * j - k));
  g->tree().fill(openvdb::CoordBBox({128, 0, 0}, {255, 127, 127}), 2.0f);      // lower tile
  g->tree().fill(openvdb::CoordBBox({4096, 0, 0}, {8191, 4095, 4095}), 3.0f);  // root tile
  g->tree().fill(openvdb::CoordBBox({0, 512, 0}, {511, 1023, 511}), 4.0f);     // upper tile
  acc.setValueOff({300, 5, 5}, 7.0f);  // an inactive non-background value
  return g;
}

class VdbStreamCheckTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    openvdb::initialize();
  }
  void TearDown() override {
    reset_memory_limit();
    TempDirTest::TearDown();
  }

  fs::path write(const openvdb::GridPtrVec& grids, std::uint32_t compression,
                 const openvdb::MetaMap& meta = {}) {
    const fs::path p = dir_ / ("g" + std::to_string(counter_++) + ".vdb");
    openvdb::io::File f(p.string());
    f.setCompression(compression);
    f.write(grids, meta);
    f.close();
    return p;
  }

  // The walk accepts the file, and OpenVDB then reads every grid.
  static void expect_accepted_and_readable(const fs::path& p) {
    ASSERT_NO_THROW(vdb_format::check_vdb_stream(p)) << p;
    openvdb::io::File f(p.string());
    f.open(false);
    for (auto it = f.beginName(); it != f.endName(); ++it)
      EXPECT_NO_THROW(f.readGrid(it.gridName())) << it.gridName();
  }

  // The message of the InputError the check must throw.
  static std::string refusal(const fs::path& p) {
    return testing::expect_input_error([&] { vdb_format::check_vdb_stream(p); }).what();
  }

  int counter_ = 0;
};

TEST_F(VdbStreamCheckTest, EveryCompressionAndPrecisionOpenVdbWritesIsAccepted) {
  using openvdb::io::COMPRESS_ACTIVE_MASK;
  using openvdb::io::COMPRESS_BLOSC;
  using openvdb::io::COMPRESS_ZIP;
  const std::uint32_t mask = COMPRESS_ACTIVE_MASK, zip = COMPRESS_ZIP, blosc = COMPRESS_BLOSC;
  for (const std::uint32_t c : {0u, mask, zip, zip | mask, blosc, blosc | mask})
    for (const bool half : {false, true}) {
      SCOPED_TRACE(::testing::Message() << "compression " << c << " half " << half);
      auto g = sparse_grid("density");
      g->setSaveFloatAsHalf(half);
      expect_accepted_and_readable(write({g}, c));
    }
}

TEST_F(VdbStreamCheckTest, OtherGridTypesInstancesEmptyGridsAndEveryMetadataTypeAreAccepted) {
  auto density = sparse_grid("density");
  auto instance = density->copyGrid();  // shares the tree: written as an instance
  instance->setName("density_instance");
  auto velocity = openvdb::Vec3SGrid::create();
  velocity->setName("vel");
  velocity->tree().setValue({1, 2, 3}, openvdb::Vec3s(1, 2, 3));
  auto empty = openvdb::FloatGrid::create(1.0f);
  empty->setName("empty");
  auto frustum = sparse_grid("frustum");
  frustum->setTransform(openvdb::math::Transform::createFrustumTransform(
      openvdb::BBoxd({0, 0, 0}, {10, 10, 10}), 0.5, 2.0, 1.0));
  auto affine = sparse_grid("affine");
  affine->setTransform(
      openvdb::math::Transform::Ptr(new openvdb::math::Transform(openvdb::math::MapBase::Ptr(
          new openvdb::math::AffineMap(openvdb::math::Mat4d(openvdb::math::Mat4d::identity()))))));
  openvdb::MetaMap meta;
  meta.insertMeta("b", openvdb::BoolMetadata(true));
  meta.insertMeta("f", openvdb::FloatMetadata(1.5f));
  meta.insertMeta("i64", openvdb::Int64Metadata(-7));
  meta.insertMeta("v3d", openvdb::Vec3DMetadata(openvdb::Vec3d(1, 2, 3)));
  meta.insertMeta("v4i", openvdb::Vec4IMetadata(openvdb::Vec4i(1, 2, 3, 4)));
  meta.insertMeta("m4d", openvdb::Mat4DMetadata(openvdb::math::Mat4d::identity()));
  meta.insertMeta("s", openvdb::StringMetadata("a string value"));
  meta.insertMeta("empty_s", openvdb::StringMetadata(""));
  const std::uint32_t none = openvdb::io::COMPRESS_NONE;
  const std::uint32_t blosc = openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK;
  for (const std::uint32_t c : {none, blosc})
    expect_accepted_and_readable(
        write({density, instance, velocity, empty, frustum, affine}, c, meta));
}

// The first blosc chunk of a leaf (2048 bytes of float values) in `b`: the
// int64 chunk size, followed by a blosc header whose cbytes (bytes 12-15)
// equals it and whose nbytes (bytes 4-7) is 2048.
std::size_t find_leaf_blosc_chunk(const Bytes& b) {
  for (std::size_t at = 0; at + 24 <= b.size(); ++at) {
    const auto n = load<std::int64_t>(b, at);
    if (n > 16 && n < 4096 && load<std::uint32_t>(b, at + 8 + 4) == 2048 &&
        load<std::uint32_t>(b, at + 8 + 12) == static_cast<std::uint32_t>(n))
      return at;
  }
  return 0;
}

TEST_F(VdbStreamCheckTest, ACompressedChunkSizeBeyondTheGridIsRefusedBeforeOpenVdbAllocatesIt) {
  // The fuzzing finding: OpenVDB's bloscFromStream did new char[size] with
  // the size as read, 128 TB from one mutated keyframe.
  Bytes b = testing::read_file_bytes(write({sparse_grid("density")}, openvdb::io::COMPRESS_BLOSC));
  const std::size_t at = find_leaf_blosc_chunk(b);
  ASSERT_GT(at, 0u);
  store<std::int64_t>(b, at, std::int64_t{1} << 47);
  testing::write_file_bytes(dir_ / "huge.vdb", b);
  const std::string msg = refusal(dir_ / "huge.vdb");
  EXPECT_NE(msg.find("grid density"), std::string::npos) << msg;
  EXPECT_NE(msg.find("runs past the grid's end"), std::string::npos) << msg;
}

TEST_F(VdbStreamCheckTest, ABloscHeaderThatDisagreesWithItsChunkIsRefused) {
  // blosc_decompress_ctx trusts the header: a larger cbytes reads past the
  // buffer OpenVDB allocated for the chunk.
  const Bytes good =
      testing::read_file_bytes(write({sparse_grid("density")}, openvdb::io::COMPRESS_BLOSC));
  const std::size_t at = find_leaf_blosc_chunk(good);
  ASSERT_GT(at, 0u);
  Bytes lies = good;
  store<std::uint32_t>(lies, at + 8 + 12, load<std::uint32_t>(good, at + 8 + 12) + 100);
  testing::write_file_bytes(dir_ / "cbytes.vdb", lies);
  EXPECT_NE(refusal(dir_ / "cbytes.vdb").find("says it holds"), std::string::npos);
  Bytes wrong_size = good;
  store<std::uint32_t>(wrong_size, at + 8 + 4, 4096);
  testing::write_file_bytes(dir_ / "nbytes.vdb", wrong_size);
  EXPECT_NE(refusal(dir_ / "nbytes.vdb").find("where 2048 are expected"), std::string::npos);
}

TEST_F(VdbStreamCheckTest, AMetadataValueOfAnotherSizeThanItsTypeIsRefused) {
  // TypedMetadata::readValue reads sizeof(T) whatever the entry says, so a
  // wrong size would put OpenVDB and the walk at different places.
  openvdb::MetaMap meta;
  meta.insertMeta("probe_entry", openvdb::Int32Metadata(5));
  Bytes b =
      testing::read_file_bytes(write({sparse_grid("density")}, openvdb::io::COMPRESS_NONE, meta));
  const std::string key = "probe_entry";
  const auto it = std::search(b.begin(), b.end(), key.begin(), key.end());
  ASSERT_NE(it, b.end());
  // name, then the type "int32" (uint32 length + 5 bytes), then the size.
  const std::size_t size_at = static_cast<std::size_t>(it - b.begin()) + key.size() + 4 + 5;
  ASSERT_EQ(load<std::uint32_t>(b, size_at), 4u);
  store<std::uint32_t>(b, size_at, 8);
  testing::write_file_bytes(dir_ / "meta.vdb", b);
  const std::string msg = refusal(dir_ / "meta.vdb");
  EXPECT_NE(msg.find("file metadata 'probe_entry'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("int32 value of 8 bytes where OpenVDB reads 4"), std::string::npos) << msg;
}

// OpenVDB reads a float grid's values as halves when the grid's metadata
// says "is_saved_as_half_float" (GridBase::saveFloatAsHalf, once readMeta has
// replaced the metadata the descriptor's "_HalfFloat" type set): found by
// the vdb_density fuzz harness, a half-float grid whose flag's name was
// mutated made OpenVDB read full floats and allocate 4.5e18 bytes for a
// chunk the walk had read as halves (fuzz/regressions/vdb_density).
TEST_F(VdbStreamCheckTest, TheGridsMetadataNotItsTypeNameSaysWhetherValuesAreHalves) {
  auto g = sparse_grid("density");
  g->setSaveFloatAsHalf(true);
  Bytes b = testing::read_file_bytes(write({g}, openvdb::io::COMPRESS_BLOSC));
  const std::string key = openvdb::GridBase::META_SAVE_HALF_FLOAT;
  const auto it = std::search(b.begin(), b.end(), key.begin(), key.end());
  ASSERT_NE(it, b.end());
  const auto at = static_cast<std::size_t>(it - b.begin());
  // The type name still ends in "_HalfFloat", but the flag is gone: OpenVDB
  // reads floats, so the halves' chunks no longer fit.
  Bytes renamed = b;
  renamed[at + key.size() - 1] = 'x';
  testing::write_file_bytes(dir_ / "renamed.vdb", renamed);
  const std::string msg = refusal(dir_ / "renamed.vdb");
  EXPECT_NE(msg.find("grid density"), std::string::npos) << msg;
  EXPECT_NE(msg.find("the file is corrupt"), std::string::npos) << msg;
  // The flag's value: name, the type "bool" (uint32 length + 4 bytes), the size, then one byte.
  const std::size_t value_at = at + key.size() + 4 + 4 + 4;
  ASSERT_EQ(b[value_at], 1);
  Bytes two = b;
  two[value_at] = 2;
  testing::write_file_bytes(dir_ / "two.vdb", two);
  EXPECT_NE(refusal(dir_ / "two.vdb").find("'is_saved_as_half_float': a bool of value 2"),
            std::string::npos)
      << refusal(dir_ / "two.vdb");
}

TEST_F(VdbStreamCheckTest, ATreeLargerThanTheMemoryLimitIsRefusedBeforeOpenVdbBuildsIt) {
  const fs::path p = write({sparse_grid("density")}, openvdb::io::COMPRESS_BLOSC);
  set_memory_limit(64 * 1024, MemoryLimitSource::kCommandLine);
  const std::string msg = refusal(p);
  EXPECT_NE(msg.find("grid density: its OpenVDB tree needs"), std::string::npos) << msg;
  reset_memory_limit();
  EXPECT_NO_THROW(vdb_format::check_vdb_stream(p));
}

TEST_F(VdbStreamCheckTest, FileVersionsOutsideTheLayoutsWalkedAreRefused) {
  // The file version is the uint32 after the 8-byte magic. OpenVDB only
  // warns about a newer one and reads on, in a layout it does not know.
  const testing::Bytes b =
      testing::read_file_bytes(write({sparse_grid("density")}, openvdb::io::COMPRESS_BLOSC));
  for (const std::uint32_t version : {221u, openvdb::OPENVDB_FILE_VERSION + 1, 4320u}) {
    testing::Bytes v = b;
    store<std::uint32_t>(v, 8, version);
    testing::write_file_bytes(dir_ / "v.vdb", v);
    const std::string msg = refusal(dir_ / "v.vdb");
    EXPECT_NE(msg.find(fmt::format("OpenVDB file version {} is", version)), std::string::npos)
        << msg;
  }
}

TEST_F(VdbStreamCheckTest, AUuidOutOfItsFormIsRefused) {
  // A fuzzing finding: OpenVDB 10 reads the UUID with boost's `is >> uuid`,
  // which stops at a character out of place, so a vertical tab among its
  // digits moved everything OpenVDB read next (a 1.6 GB metadata name) away
  // from where the walk read. The UUID follows the 8-byte magic, the version,
  // the library version and the offsets flag (21 bytes).
  const testing::Bytes b =
      testing::read_file_bytes(write({sparse_grid("density")}, openvdb::io::COMPRESS_BLOSC));
  for (const std::size_t at : {21u + 0u, 21u + 8u, 21u + 35u}) {
    testing::Bytes v = b;
    v[at] = '\v';
    testing::write_file_bytes(dir_ / "u.vdb", v);
    EXPECT_NE(refusal(dir_ / "u.vdb").find("header: its UUID is not 36 characters"),
              std::string::npos)
        << "at " << at;
  }
}

TEST_F(VdbStreamCheckTest, EveryTruncationIsRefused) {
  const Bytes b =
      testing::read_file_bytes(write({sparse_grid("density")}, openvdb::io::COMPRESS_BLOSC));
  for (std::size_t len = 0; len < b.size(); len += 1 + len / 16) {
    testing::write_file_bytes(dir_ / "cut.vdb",
                              Bytes(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(len)));
    EXPECT_NE(refusal(dir_ / "cut.vdb"), "") << "cut at " << len << " of " << b.size();
  }
}

}  // namespace
}  // namespace obscura
