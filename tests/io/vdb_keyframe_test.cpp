#include "obscura/io/vdb_keyframe.h"

#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <typeinfo>
#include <vector>

#include "obscura/core/error.h"
#include "obscura/core/mat3.h"
#include "support/temp_dir_test.h"
#include "support/vdb_edit.h"

namespace obscura {
namespace {

namespace fs = std::filesystem;

class VdbKeyframeTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    openvdb::initialize();  // the tests write files by hand with OpenVDB directly
  }

  // Names of everything in dir_, to check that failed writes leave nothing.
  std::vector<std::string> dir_entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }
};

// A 13x7x5 grid (not a multiple of the 8³ VDB leaf) with 3 spectral samples,
// random values and about 40% exact zeros, rotated and offset.
VoxelGrid make_random_grid(unsigned seed) {
  GridPlacement p;
  p.origin_m = {-12.3, 4.56, 100.7};
  p.voxel_size_m = 0.37;
  p.rotation = rotation_from_euler_deg({20.0, -35.0, 110.0});
  VoxelGrid grid({13, 7, 5}, p, {0.55, 3.9, 10.6});
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const std::size_t n = grid.dims().count();
  for (int c = 0; c < grid.channel_count(); ++c) {
    float* v = grid.channel(c);
    const bool is_g = c >= 2 * grid.spectral_count() && c < 3 * grid.spectral_count();
    const bool is_t = c == grid.channel_count() - 1;
    for (std::size_t i = 0; i < n; ++i) {
      if (u01(rng) < 0.4f) {
        v[i] = 0.0f;
        continue;
      }
      v[i] = is_g ? 1.98f * u01(rng) - 0.99f : is_t ? 250.0f + 150.0f * u01(rng) : 5.0f * u01(rng);
    }
  }
  return grid;
}

// Expects `fn` to throw InputError whose message names `file` and `field`.
void expect_input_error(const std::function<void()>& fn, const fs::path& file,
                        const std::string& field) {
  try {
    fn();
    ADD_FAILURE() << "expected InputError naming " << file << " and " << field;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(file.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find(field), std::string::npos) << "message lacks '" << field << "': " << msg;
  }
}

void expect_read_error(const fs::path& file, const std::string& field) {
  expect_input_error([&] { read_cloud_keyframe(file); }, file, field);
}

using testing::find_grid;
using testing::remove_grid;
using testing::rewrite_by_hand;

TEST_F(VdbKeyframeTest, RoundTripIsExact) {
  const VoxelGrid grid = make_random_grid(7);
  const fs::path path = dir_ / "frame_0001.vdb";
  write_cloud_keyframe(path, grid, 12.5, {{"source", "unit test"}, {"solver", "x,y=1"}});
  EXPECT_EQ(dir_entries(), std::vector<std::string>{"frame_0001.vdb"});  // no temp left

  const CloudKeyframe kf = read_cloud_keyframe(path);
  ASSERT_TRUE(kf.grid);
  const VoxelGrid& back = *kf.grid;
  EXPECT_EQ(kf.time_s, 12.5);
  EXPECT_EQ(back.dims(), grid.dims());
  EXPECT_EQ(back.wavelengths_um(), grid.wavelengths_um());  // exact, via %.17g
  ASSERT_EQ(back.channel_count(), grid.channel_count());
  for (int c = 0; c < grid.channel_count(); ++c)
    EXPECT_EQ(std::memcmp(back.channel(c), grid.channel(c), grid.dims().count() * sizeof(float)), 0)
        << grid.channel_name(c);

  // The exact placement travels beside the transform ("placement" metadata):
  // origin, voxel size and rotation come back bit for bit.
  const GridPlacement& p = back.placement();
  EXPECT_EQ(p.voxel_size_m, grid.placement().voxel_size_m);
  EXPECT_EQ(p.origin_m, grid.placement().origin_m);
  EXPECT_EQ(p.rotation, grid.placement().rotation);
  // A world point maps to the same index either way.
  const Vec3 w = grid.placement().index_to_world({3.25, 6.0, 1.5});
  const Vec3 i = p.world_to_index(w);
  EXPECT_NEAR(i.x, 3.25, 1e-12);
  EXPECT_NEAR(i.y, 6.0, 1e-12);
  EXPECT_NEAR(i.z, 1.5, 1e-12);
}

TEST_F(VdbKeyframeTest, FileFollowsTheDocumentedConventions) {
  const VoxelGrid grid = make_random_grid(11);
  const fs::path path = dir_ / "k.vdb";
  write_cloud_keyframe(path, grid, 3.0);

  openvdb::io::File f(path.string());
  f.open(false);
  const openvdb::MetaMap::Ptr meta = f.getMetadata();
  EXPECT_EQ(meta->metaValue<std::string>("obscura_format"), "cloud-keyframe");
  EXPECT_EQ(meta->metaValue<openvdb::Int32>("obscura_format_version"), 1);
  EXPECT_EQ(meta->metaValue<std::string>("obscura_form"), "spectral");
  EXPECT_EQ(meta->metaValue<openvdb::Int32>("spectral_count"), 3);
  char expect_w[128];
  std::snprintf(expect_w, sizeof expect_w, "%.17g,%.17g,%.17g", 0.55, 3.9, 10.6);
  EXPECT_EQ(meta->metaValue<std::string>("wavelengths_um"), expect_w);
  EXPECT_EQ(meta->metaValue<openvdb::Vec3i>("dims"), openvdb::Vec3i(13, 7, 5));
  EXPECT_EQ(meta->metaValue<double>("time_s"), 3.0);

  // Sparse storage: exactly the non-zero voxels are active, at Coord(i,j,k).
  for (int c = 0; c < grid.channel_count(); ++c) {
    const std::string name = grid.channel_name(c);
    ASSERT_TRUE(f.hasGrid(name)) << name;
    auto g = openvdb::gridPtrCast<openvdb::FloatGrid>(f.readGrid(name));
    ASSERT_TRUE(g) << name;
    const float* v = grid.channel(c);
    std::size_t nonzero = 0;
    for (std::size_t i = 0; i < grid.dims().count(); ++i) nonzero += v[i] != 0.0f;
    EXPECT_EQ(g->activeVoxelCount(), nonzero) << name;
    EXPECT_EQ(g->tree().getValue(openvdb::Coord(4, 5, 2)), v[grid.index(4, 5, 2)]) << name;
    EXPECT_EQ(g->getGridClass(),
              c < 2 * grid.spectral_count() ? openvdb::GRID_FOG_VOLUME : openvdb::GRID_UNKNOWN);
  }
  auto t = f.readGrid("temperature");
  EXPECT_EQ(t->metaValue<std::string>("units"), "K");
  auto s = f.readGrid("sigma_s_002");
  EXPECT_EQ(s->metaValue<std::string>("units"), "1/m");
  EXPECT_EQ(s->metaValue<openvdb::Int32>("spectral_index"), 2);
  EXPECT_EQ(s->metaValue<double>("wavelength_um"), 10.6);
  EXPECT_EQ(f.readGrid("g_000")->metaValue<std::string>("units"), "1");
  // The transform maps index (i,j,k) to the voxel centre.
  const openvdb::Vec3d w = t->transform().indexToWorld(openvdb::Vec3d(2, 3, 4));
  const Vec3 expect = grid.placement().index_to_world({2, 3, 4});
  EXPECT_NEAR(w.x(), expect.x, 1e-12);
  EXPECT_NEAR(w.y(), expect.y, 1e-12);
  EXPECT_NEAR(w.z(), expect.z, 1e-12);
}

TEST_F(VdbKeyframeTest, SingleVoxelRoundTrip) {
  GridPlacement p;
  p.origin_m = {1.0, 2.0, 3.0};
  p.voxel_size_m = 0.1;
  VoxelGrid grid({1, 1, 1}, p, {4.0});
  grid.sigma_a(0)[0] = 0.25f;
  grid.sigma_s(0)[0] = 0.0f;  // stored as an inactive background voxel
  grid.g(0)[0] = -0.3f;
  grid.temperature()[0] = 300.0f;
  const fs::path path = dir_ / "one.vdb";
  write_cloud_keyframe(path, grid, 0.0);
  const CloudKeyframe kf = read_cloud_keyframe(path);
  const VoxelGrid& b = *kf.grid;
  EXPECT_EQ(b.dims(), (GridDims{1, 1, 1}));
  EXPECT_EQ(b.wavelengths_um(), std::vector<double>{4.0});
  EXPECT_EQ(b.sigma_a(0)[0], 0.25f);
  EXPECT_EQ(b.sigma_s(0)[0], 0.0f);
  EXPECT_EQ(b.g(0)[0], -0.3f);
  EXPECT_EQ(b.temperature()[0], 300.0f);
  EXPECT_EQ(kf.time_s, 0.0);
  EXPECT_EQ(b.placement().voxel_size_m, 0.1);
  EXPECT_EQ(b.placement().rotation, Mat3::identity());
  EXPECT_EQ(b.placement().origin_m.z, 3.0);
}

TEST_F(VdbKeyframeTest, InspectSummarises) {
  const VoxelGrid grid = make_random_grid(3);
  const fs::path path = dir_ / "info.vdb";
  write_cloud_keyframe(path, grid, 7.25, {{"source", "les run 4"}});
  const KeyframeInfo info = inspect_cloud_keyframe(path);
  EXPECT_EQ(info.dims, grid.dims());
  EXPECT_EQ(info.wavelengths_um, grid.wavelengths_um());
  EXPECT_EQ(info.time_s, 7.25);
  EXPECT_EQ(info.memory_bytes, grid.memory_bytes());
  EXPECT_GT(info.file_bytes, 0u);
  ASSERT_EQ(info.channels.size(), static_cast<std::size_t>(grid.channel_count()));
  const auto& t = info.channels.back();
  EXPECT_EQ(t.name, "temperature");
  EXPECT_EQ(t.units, "K");
  EXPECT_EQ(t.min, 0.0f);  // zeros count
  EXPECT_GE(t.max, 250.0f);
  EXPECT_EQ(info.channels[0].units, "1/m");
  EXPECT_EQ(info.metadata.at("source"), "les run 4");
  EXPECT_EQ(info.metadata.at("obscura_format"), "cloud-keyframe");
}

// ---- read errors -----------------------------------------------------------

class VdbKeyframeErrorTest : public VdbKeyframeTest {
 protected:
  void SetUp() override {
    VdbKeyframeTest::SetUp();
    good_ = dir_ / "good.vdb";
    write_cloud_keyframe(good_, make_random_grid(5), 1.0);
    bad_ = dir_ / "bad.vdb";
  }
  void edit(const std::function<void(openvdb::GridPtrVec&, openvdb::MetaMap&)>& fn) {
    rewrite_by_hand(good_, bad_, fn);
  }
  fs::path good_, bad_;
};

TEST_F(VdbKeyframeErrorTest, UnmodifiedCopyReads) {
  edit([](auto&, auto&) {});
  EXPECT_NO_THROW(read_cloud_keyframe(bad_));  // the harness itself does not break files
}

TEST_F(VdbKeyframeErrorTest, MissingGrid) {
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) { remove_grid(g, "sigma_s_001"); });
  expect_read_error(bad_, "sigma_s_001");
}

TEST_F(VdbKeyframeErrorTest, MissingTemperatureGrid) {
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) { remove_grid(g, "temperature"); });
  expect_read_error(bad_, "temperature");
}

TEST_F(VdbKeyframeErrorTest, GridOfWrongType) {
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) {
    auto old = find_grid(g, "g_001");
    remove_grid(g, "g_001");
    auto d = openvdb::DoubleGrid::create(0.0);
    d->setName("g_001");
    d->setTransform(old->transform().copy());
    g.push_back(d);
  });
  expect_read_error(bad_, "g_001");
}

TEST_F(VdbKeyframeErrorTest, ExtraSpectralGrid) {
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) {
    auto extra = find_grid(g, "sigma_a_000")->deepCopy();
    extra->setName("sigma_a_003");
    g.push_back(extra);
  });
  expect_read_error(bad_, "sigma_a_003");
}

TEST_F(VdbKeyframeErrorTest, MissingMetadata) {
  for (const char* key : {"time_s", "obscura_format", "wavelengths_um", "dims", "spectral_count",
                          "coefficient_units"}) {
    edit([&](openvdb::GridPtrVec&, openvdb::MetaMap& m) { m.removeMeta(key); });
    expect_read_error(bad_, key);
  }
}

TEST_F(VdbKeyframeErrorTest, WrongMetadataType) {
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) {
    m.removeMeta("spectral_count");
    m.insertMeta("spectral_count", openvdb::StringMetadata("3"));
  });
  expect_read_error(bad_, "spectral_count");
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) {
    m.removeMeta("dims");
    m.insertMeta("dims", openvdb::Vec3DMetadata(openvdb::Vec3d(13, 7, 5)));
  });
  expect_read_error(bad_, "dims");
}

TEST_F(VdbKeyframeErrorTest, WrongFormatAndNewerVersion) {
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) {
    m.insertMeta("obscura_format", openvdb::StringMetadata("something-else"));
  });
  expect_read_error(bad_, "obscura_format");
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) {
    m.insertMeta("obscura_format_version", openvdb::Int32Metadata(2));
  });
  expect_read_error(bad_, "obscura_format_version");
}

TEST_F(VdbKeyframeErrorTest, WavelengthsDoNotMatchSpectralCount) {
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) {
    m.insertMeta("wavelengths_um", openvdb::StringMetadata("0.55,3.9"));
  });
  expect_read_error(bad_, "wavelengths_um");
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) {
    m.insertMeta("wavelengths_um", openvdb::StringMetadata("0.55,abc,10.6"));
  });
  expect_read_error(bad_, "wavelengths_um");
}

TEST_F(VdbKeyframeErrorTest, NegativeCoefficient) {
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) {
    find_grid(g, "sigma_a_001")->tree().setValue(openvdb::Coord(2, 3, 4), -0.5f);
  });
  expect_read_error(bad_, "sigma_a_001 voxel (2,3,4)");
}

TEST_F(VdbKeyframeErrorTest, NaNValue) {
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) {
    find_grid(g, "sigma_s_000")
        ->tree()
        .setValue(openvdb::Coord(0, 0, 0), std::numeric_limits<float>::quiet_NaN());
  });
  expect_read_error(bad_, "sigma_s_000 voxel (0,0,0)");
}

TEST_F(VdbKeyframeErrorTest, AsymmetryOutsideOpenInterval) {
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) {
    find_grid(g, "g_002")->tree().setValue(openvdb::Coord(12, 6, 4), 1.0f);
  });
  expect_read_error(bad_, "g_002 voxel (12,6,4)");
}

TEST_F(VdbKeyframeErrorTest, ActiveVoxelOutsideDims) {
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) {
    find_grid(g, "temperature")->tree().setValue(openvdb::Coord(13, 0, 0), 300.0f);
  });
  expect_read_error(bad_, "temperature");
}

TEST_F(VdbKeyframeErrorTest, HugeDims) {
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) {
    m.insertMeta("dims", openvdb::Vec3IMetadata(openvdb::Vec3i(100000, 100000, 100000)));
  });
  expect_read_error(bad_, "dims");
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) {
    m.insertMeta("dims", openvdb::Vec3IMetadata(openvdb::Vec3i(13, 0, 5)));
  });
  expect_read_error(bad_, "dims");
}

TEST_F(VdbKeyframeErrorTest, NonUniformOrMismatchedTransform) {
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) {
    for (auto& grid : g) grid->transform().postScale(openvdb::Vec3d(1.0, 2.0, 1.0));
  });
  expect_read_error(bad_, "temperature");
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) {
    find_grid(g, "sigma_a_002")->transform().postTranslate(openvdb::Vec3d(0.5, 0, 0));
  });
  expect_read_error(bad_, "sigma_a_002");
}

TEST_F(VdbKeyframeErrorTest, PlacementRecordMustMatchTransform) {
  // Moving every grid but not the exact placement record is an inconsistent edit.
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) {
    for (auto& grid : g) grid->transform().postTranslate(openvdb::Vec3d(3.0, 0, 0));
  });
  expect_read_error(bad_, "placement");
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) {
    m.removeMeta("placement");
    m.insertMeta("placement", openvdb::StringMetadata("origin_m=1,2"));
  });
  expect_read_error(bad_, "placement");
  // Files from other tools carry no record: the transform alone places the grid.
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) { m.removeMeta("placement"); });
  EXPECT_NO_THROW(read_cloud_keyframe(bad_));
}

TEST_F(VdbKeyframeErrorTest, FormIsSpectralWhenAbsentAndMustBeKnown) {
  // Files from other tools (and obscura before the species form) have no obscura_form.
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) { m.removeMeta("obscura_form"); });
  EXPECT_EQ(inspect_cloud_keyframe(bad_).form, "spectral");
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) {
    m.insertMeta("obscura_form", openvdb::StringMetadata("spectra"));
  });
  expect_read_error(bad_, "obscura_form");
  // A species-form file needs its species grids, not spectral ones.
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) {
    m.insertMeta("obscura_form", openvdb::StringMetadata("species"));
  });
  expect_read_error(bad_, "concentration_units");
}

TEST_F(VdbKeyframeErrorTest, UnreadableAndNonVdbFiles) {
  const fs::path missing = dir_ / "missing.vdb";
  expect_input_error([&] { read_cloud_keyframe(missing); }, missing, "no such file");

  const fs::path text = dir_ / "notes.vdb";
  std::ofstream(text) << "this is not a VDB file\n";
  expect_input_error([&] { read_cloud_keyframe(text); }, text, "OpenVDB");

  // A VDB file cut in half.
  const fs::path cut = dir_ / "cut.vdb";
  fs::copy_file(good_, cut);
  fs::resize_file(cut, fs::file_size(good_) / 2);
  EXPECT_THROW(read_cloud_keyframe(cut), InputError);

  expect_input_error([&] { read_cloud_keyframe(dir_); }, dir_, "not a regular file");
}

// A keyframe cut at any length is an InputError naming the file, never
// std::bad_alloc: at 100 bytes OpenVDB allocated 5-13 GB, at 300-500 bytes it
// ended in bad_alloc, and a file one byte short read without complaint.
TEST_F(VdbKeyframeErrorTest, TruncatedAtAnyLengthIsAnInputError) {
  const std::uintmax_t size = fs::file_size(good_);
  const fs::path cut = dir_ / "cut.vdb";
  std::vector<std::uintmax_t> lengths;
  for (std::uintmax_t n = 0; n < std::min<std::uintmax_t>(size, 1200); ++n) lengths.push_back(n);
  for (std::uintmax_t n = 1200; n < size; n += 251) lengths.push_back(n);
  lengths.push_back(size - 1);
  for (const std::uintmax_t n : lengths) {
    fs::copy_file(good_, cut, fs::copy_options::overwrite_existing);
    fs::resize_file(cut, n);
    try {
      read_cloud_keyframe(cut);
      ADD_FAILURE() << "a keyframe cut to " << n << " of " << size << " bytes was read";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), cut.string()) << n;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "cut to " << n << " bytes: " << typeid(e).name() << ": " << e.what();
    }
  }
  // The check accepts the whole file.
  EXPECT_NO_THROW(read_cloud_keyframe(good_));
}

// ---- writer ----------------------------------------------------------------

TEST_F(VdbKeyframeTest, FailedWritesLeaveNothingBehind) {
  const VoxelGrid grid = make_random_grid(9);
  // The "directory" is a regular file: the writer cannot create it.
  const fs::path blocker = dir_ / "blocker";
  std::ofstream(blocker) << "x";
  EXPECT_THROW(write_cloud_keyframe(blocker / "sub" / "k.vdb", grid, 1.0), Error);
  EXPECT_THROW(write_cloud_keyframe(blocker / "k.vdb", grid, 1.0), Error);
  EXPECT_EQ(dir_entries(), std::vector<std::string>{"blocker"});

  // Invalid data, time or metadata: refused before anything is written.
  VoxelGrid bad = make_random_grid(9);
  bad.sigma_s(1)[bad.index(1, 2, 3)] = -1.0f;
  const fs::path out = dir_ / "k.vdb";
  expect_input_error([&] { write_cloud_keyframe(out, bad, 1.0); }, out,
                     "sigma_s_001 voxel (1,2,3)");
  expect_input_error([&] { write_cloud_keyframe(out, grid, std::nan("")); }, out, "time_s");
  expect_input_error([&] { write_cloud_keyframe(out, grid, 1.0, {{"dims", "1"}}); }, out, "dims");
  expect_input_error(
      [&] {
        write_cloud_keyframe(out, grid, 1.0, {{"obscura_form", "x"}});
      },
      out, "obscura_form");
  EXPECT_EQ(dir_entries(), std::vector<std::string>{"blocker"});
}

TEST_F(VdbKeyframeTest, OverwriteReplacesWholeFile) {
  const fs::path path = dir_ / "k.vdb";
  write_cloud_keyframe(path, make_random_grid(1), 1.0);
  VoxelGrid small({2, 2, 2}, GridPlacement{}, {1.0, 2.0});
  small.temperature()[0] = 280.0f;
  write_cloud_keyframe(path, small, 2.0);
  const CloudKeyframe kf = read_cloud_keyframe(path);
  EXPECT_EQ(kf.grid->dims(), (GridDims{2, 2, 2}));
  EXPECT_EQ(kf.time_s, 2.0);
  EXPECT_EQ(kf.grid->temperature()[0], 280.0f);
  EXPECT_EQ(dir_entries(), std::vector<std::string>{"k.vdb"});
}

}  // namespace
}  // namespace obscura
