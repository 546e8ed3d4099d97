// Keyframes in the compact species form: a round trip that reads back to
// expand_species bit for bit, the documented file layout, `obscura info`, and
// malformed files whose errors name the file and the grid or metadata field.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

#include "obscura/core/error.h"
#include "obscura/core/mat3.h"
#include "obscura/io/vdb_keyframe.h"
#include "obscura/medium/species_optics.h"
#include "support/cli_runner.h"
#include "support/input_error.h"
#include "support/temp_dir_test.h"
#include "support/vdb_edit.h"

namespace obscura {
namespace {

namespace fs = std::filesystem;
using testing::contains;
using testing::find_grid;
using testing::remove_grid;

// Two species on a rotated 13×7×5 grid (not a multiple of the 8³ VDB leaf),
// three wavelengths, random concentrations with about 40 % exact zeros.
SpeciesCloud make_random_cloud(unsigned seed) {
  SpeciesCloud c;
  c.dims = {13, 7, 5};
  c.placement.origin_m = {-12.3, 4.56, 100.7};
  c.placement.voxel_size_m = 0.37;
  c.placement.rotation = rotation_from_euler_deg({20.0, -35.0, 110.0});
  c.wavelengths_um = {0.55, 3.9, 10.6};
  // Coefficients with many digits: the optics table must round-trip exactly.
  c.species = {
      {"phosphorus_smoke",
       c.wavelengths_um,
       {0.0123456789012345, 0.31, 0.35},
       {3.14159265358979, 0.0271828182845905, 0.0},
       {0.7071067811865476, 0.25, 0.0}},
      {"soot", c.wavelengths_um, {7.1, 1.2345e-3, 0.9}, {2.2, 0.1, 0.01}, {0.3, -0.1, 1.0 / 3.0}}};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const std::size_t n = c.dims.count();
  c.concentration_g_m3.assign(2, std::vector<float>(n, 0.0f));
  for (auto& conc : c.concentration_g_m3)
    for (float& v : conc) v = u01(rng) < 0.4f ? 0.0f : 5.0f * u01(rng);
  for (std::size_t v = 0; v < n; ++v) c.temperature_k.push_back(250.0f + 150.0f * u01(rng));
  return c;
}

bool same_grids(const VoxelGrid& a, const VoxelGrid& b) {
  if (!(a.dims() == b.dims()) || a.wavelengths_um() != b.wavelengths_um()) return false;
  for (int c = 0; c < a.channel_count(); ++c)
    if (std::memcmp(a.channel(c), b.channel(c), a.dims().count() * sizeof(float)) != 0)
      return false;
  return true;
}

class SpeciesKeyframeTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    openvdb::initialize();  // the tests read and edit files with OpenVDB directly
    cloud_ = make_random_cloud(5);
    good_ = dir_ / "good.vdb";
    bad_ = dir_ / "bad.vdb";
    write_species_keyframe(good_, cloud_, 2.5, {{"source", "unit test"}});
  }
  void edit(const std::function<void(openvdb::GridPtrVec&, openvdb::MetaMap&)>& fn) {
    testing::rewrite_by_hand(good_, bad_, fn);
  }
  // The read error for bad_, which must name the file and `field`.
  std::string read_error(const std::string& field) {
    const InputError e = testing::expect_input_error([&] { read_cloud_keyframe(bad_); });
    const std::string msg = e.what();
    EXPECT_TRUE(contains(msg, bad_.string())) << msg;
    EXPECT_TRUE(contains(msg, field)) << "message lacks '" << field << "': " << msg;
    return msg;
  }
  void set_optics_json(const nlohmann::json& doc) {
    edit([&](openvdb::GridPtrVec&, openvdb::MetaMap& m) {
      m.insertMeta("species_optics", openvdb::StringMetadata(doc.dump()));
    });
  }
  std::string read_error_after(const nlohmann::json& optics,
                               const std::string& field = "species_optics") {
    set_optics_json(optics);
    return read_error(field);
  }
  nlohmann::json optics_json() const {
    openvdb::io::File f(good_.string());
    f.open(false);
    return nlohmann::json::parse(f.getMetadata()->metaValue<std::string>("species_optics"));
  }
  SpeciesCloud cloud_;
  fs::path good_, bad_;
};

TEST_F(SpeciesKeyframeTest, RoundTripReadsAsTheExpandedCloudBitForBit) {
  const CloudKeyframe kf = read_cloud_keyframe(good_);
  ASSERT_TRUE(kf.grid);
  EXPECT_EQ(kf.time_s, 2.5);
  const VoxelGrid expected = expand_species(cloud_, "memory");
  EXPECT_TRUE(same_grids(*kf.grid, expected));
  // Not a trivial grid: both species and the mixing are exercised.
  std::size_t mixed = 0;
  for (std::size_t v = 0; v < cloud_.dims.count(); ++v)
    mixed += cloud_.concentration_g_m3[0][v] > 0 && cloud_.concentration_g_m3[1][v] > 0;
  EXPECT_GT(mixed, 50u);
  const GridPlacement& p = kf.grid->placement();
  EXPECT_EQ(p.origin_m, cloud_.placement.origin_m);
  EXPECT_EQ(p.voxel_size_m, cloud_.placement.voxel_size_m);
  EXPECT_EQ(p.rotation, cloud_.placement.rotation);
  // A spectral keyframe of the expanded grid reads back to the same grid.
  write_cloud_keyframe(dir_ / "spectral.vdb", expected, 2.5);
  EXPECT_TRUE(same_grids(*read_cloud_keyframe(dir_ / "spectral.vdb").grid, *kf.grid));
}

TEST_F(SpeciesKeyframeTest, FileFollowsTheDocumentedConventions) {
  openvdb::io::File f(good_.string());
  f.open(false);
  const openvdb::MetaMap::Ptr meta = f.getMetadata();
  EXPECT_EQ(meta->metaValue<std::string>("obscura_format"), "cloud-keyframe");
  EXPECT_EQ(meta->metaValue<openvdb::Int32>("obscura_format_version"), 1);
  EXPECT_EQ(meta->metaValue<std::string>("obscura_form"), "species");
  EXPECT_EQ(meta->metaValue<openvdb::Int32>("species_count"), 2);
  EXPECT_EQ(meta->metaValue<openvdb::Int32>("spectral_count"), 3);
  EXPECT_EQ(meta->metaValue<std::string>("concentration_units"), "g/m3");
  EXPECT_EQ(meta->metaValue<std::string>("temperature_units"), "K");
  EXPECT_EQ(meta->metaValue<std::string>("source"), "unit test");
  EXPECT_FALSE((*meta)["coefficient_units"]);
  const auto optics = nlohmann::json::parse(meta->metaValue<std::string>("species_optics"));
  ASSERT_EQ(optics.size(), 2u);
  EXPECT_EQ(optics[1]["name"], "soot");
  EXPECT_EQ(optics[0]["mass_scattering_m2_g"][0].get<double>(), 3.14159265358979);
  EXPECT_EQ(optics[1]["asymmetry"][2].get<double>(), 1.0 / 3.0);
  // Grids: concentration_000, concentration_001, temperature; no spectral grids.
  std::vector<std::string> names;
  for (auto it = f.beginName(); it != f.endName(); ++it) names.push_back(*it);
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names,
            (std::vector<std::string>{"concentration_000", "concentration_001", "temperature"}));
  auto c1 = openvdb::gridPtrCast<openvdb::FloatGrid>(f.readGrid("concentration_001"));
  EXPECT_EQ(c1->metaValue<std::string>("units"), "g/m3");
  EXPECT_EQ(c1->metaValue<std::string>("species"), "soot");
  EXPECT_EQ(c1->getGridClass(), openvdb::GRID_FOG_VOLUME);
  std::size_t nonzero = 0;
  for (float v : cloud_.concentration_g_m3[1]) nonzero += v != 0.0f;
  EXPECT_EQ(c1->activeVoxelCount(), nonzero);  // sparse: zeros are background
  const std::size_t v = 4 + 13 * (5 + 7 * 2);
  EXPECT_EQ(c1->tree().getValue(openvdb::Coord(4, 5, 2)), cloud_.concentration_g_m3[1][v]);
  auto t = f.readGrid("temperature");
  EXPECT_EQ(t->metaValue<std::string>("units"), "K");
  const openvdb::Vec3d w = t->transform().indexToWorld(openvdb::Vec3d(2, 3, 4));
  const Vec3 expect = cloud_.placement.index_to_world({2, 3, 4});
  EXPECT_NEAR(w.x(), expect.x, 1e-12);
  EXPECT_NEAR(w.y(), expect.y, 1e-12);
  EXPECT_NEAR(w.z(), expect.z, 1e-12);
}

TEST_F(SpeciesKeyframeTest, InspectAndInfoNameTheFormAndSpecies) {
  const KeyframeInfo info = inspect_cloud_keyframe(good_);
  EXPECT_EQ(info.form, "species");
  ASSERT_EQ(info.species.size(), 2u);
  EXPECT_EQ(info.species[0].optics.name, "phosphorus_smoke");
  EXPECT_EQ(info.species[1].optics.asymmetry, cloud_.species[1].asymmetry);
  EXPECT_EQ(info.species[1].concentration.name, "concentration_001");
  EXPECT_EQ(info.species[1].concentration.units, "g/m3");
  EXPECT_EQ(info.species[0].concentration.min, 0.0f);
  EXPECT_GT(info.species[0].concentration.max, 4.0f);
  EXPECT_EQ(info.compact_bytes, 3 * cloud_.dims.count() * sizeof(float));
  EXPECT_EQ(info.memory_bytes, 10 * cloud_.dims.count() * sizeof(float));
  EXPECT_EQ(info.channels.size(), 10u);  // the expanded grid's channels
  EXPECT_EQ(info.channels[0].name, "sigma_a_000");

  testing::CliResult r = testing::run_cli("info " + good_.string() + " --json", dir_);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["form"], "species");
  EXPECT_EQ(j["species"][1]["name"], "soot");
  EXPECT_EQ(j["species"][1]["concentration"]["name"], "concentration_001");
  r = testing::run_cli("info " + good_.string(), dir_);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "species form")) << r.out;
  EXPECT_TRUE(contains(r.out, "soot")) << r.out;
  EXPECT_TRUE(contains(r.out, "concentration_001")) << r.out;
}

// ---- read errors -----------------------------------------------------------

TEST_F(SpeciesKeyframeTest, UnmodifiedCopyReads) {
  edit([](auto&, auto&) {});
  EXPECT_NO_THROW(read_cloud_keyframe(bad_));  // the harness itself does not break files
}

TEST_F(SpeciesKeyframeTest, MissingOrExtraGrids) {
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) { remove_grid(g, "concentration_001"); });
  read_error("concentration_001");
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) { remove_grid(g, "temperature"); });
  read_error("temperature");
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) {
    auto extra = find_grid(g, "concentration_000")->deepCopy();
    extra->setName("concentration_002");
    g.push_back(extra);
  });
  read_error("concentration_002");
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) {
    auto extra = find_grid(g, "concentration_000")->deepCopy();
    extra->setName("sigma_a_000");
    g.push_back(extra);
  });
  read_error("sigma_a_000");
}

TEST_F(SpeciesKeyframeTest, BadSpeciesOptics) {
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) { m.removeMeta("species_optics"); });
  read_error("species_optics");
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) {
    m.insertMeta("species_optics", openvdb::StringMetadata("[{\"name\": \"soot\", "));
  });
  EXPECT_TRUE(contains(read_error("species_optics"), "JSON"));
  set_optics_json({{"name", "soot"}});
  read_error("species_optics");  // not an array
  nlohmann::json doc = optics_json();
  doc.erase(1);
  EXPECT_TRUE(contains(read_error_after(doc), "species_count"));
  doc = optics_json();
  doc[1]["asymmetry"] = {0.3, -0.1};
  read_error_after(doc, "species_optics/1/asymmetry");
  doc = optics_json();
  doc[0]["mass_absorption_m2_g"][1] = -0.31;
  read_error_after(doc, "species_optics/0/mass_absorption_m2_g/1");
  doc = optics_json();
  doc[1]["asymmetry"][0] = 1.5;
  read_error_after(doc, "species_optics/1/asymmetry/0");
  doc = optics_json();
  doc[0]["colour"] = "white";
  read_error_after(doc, "species_optics/0/colour");
  doc = optics_json();
  doc[1].erase("mass_scattering_m2_g");
  read_error_after(doc, "species_optics/1/mass_scattering_m2_g");
  doc = optics_json();
  doc[0]["name"] = 7;
  read_error_after(doc, "species_optics/0/name");
}

TEST_F(SpeciesKeyframeTest, OpticsAtOtherWavelengthsNameTheSpecies) {
  nlohmann::json doc = optics_json();
  doc[1]["wavelengths_um"] = {0.55, 4.0, 10.6};
  const std::string msg = read_error_after(doc, "species_optics/1/wavelengths_um");
  EXPECT_TRUE(contains(msg, "'soot'")) << msg;
  // The file's wavelengths changed under the optics: the same mismatch.
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) {
    m.insertMeta("wavelengths_um", openvdb::StringMetadata("0.55,3.9,10.7"));
  });
  EXPECT_TRUE(contains(read_error("species_optics/0/wavelengths_um"), "'phosphorus_smoke'"));
}

TEST_F(SpeciesKeyframeTest, BadMetadata) {
  for (const char* key : {"species_count", "concentration_units", "temperature_units", "time_s",
                          "dims", "spectral_count", "wavelengths_um"}) {
    edit([&](openvdb::GridPtrVec&, openvdb::MetaMap& m) { m.removeMeta(key); });
    read_error(key);
  }
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) {
    m.insertMeta("species_count", openvdb::Int32Metadata(3));
  });
  read_error("species_optics");  // lists 2 species but species_count is 3
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) {
    m.insertMeta("species_count", openvdb::Int32Metadata(0));
  });
  read_error("species_count");
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) {
    m.insertMeta("concentration_units", openvdb::StringMetadata("kg/m3"));
  });
  read_error("concentration_units");
  edit([](openvdb::GridPtrVec&, openvdb::MetaMap& m) {
    m.insertMeta("dims", openvdb::Vec3IMetadata(openvdb::Vec3i(100000, 100000, 100000)));
  });
  read_error("dims");
}

TEST_F(SpeciesKeyframeTest, BadGrids) {
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) {
    find_grid(g, "concentration_001")->tree().setValue(openvdb::Coord(2, 3, 4), -0.5f);
  });
  read_error("concentration_001 voxel (2,3,4)");
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) {
    find_grid(g, "concentration_000")->tree().setValue(openvdb::Coord(13, 0, 0), 1.0f);
  });
  read_error("concentration_000");  // an active voxel outside the dims
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) {
    find_grid(g, "concentration_001")->insertMeta("species", openvdb::StringMetadata("fog oil"));
  });
  read_error("concentration_001.species");
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) {
    find_grid(g, "concentration_000")->insertMeta("units", openvdb::StringMetadata("1/m"));
  });
  read_error("concentration_000.units");
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) {
    find_grid(g, "concentration_001")->transform().postTranslate(openvdb::Vec3d(0.5, 0, 0));
  });
  read_error("concentration_001");
  edit([](openvdb::GridPtrVec& g, openvdb::MetaMap&) {
    auto old = find_grid(g, "concentration_000");
    remove_grid(g, "concentration_000");
    auto d = openvdb::DoubleGrid::create(0.0);
    d->setName("concentration_000");
    d->setTransform(old->transform().copy());
    g.push_back(d);
  });
  read_error("concentration_000");
}

// ---- writer ----------------------------------------------------------------

TEST_F(SpeciesKeyframeTest, WriterRefusesBadInputAndLeavesNothing) {
  const fs::path out = dir_ / "out.vdb";
  const auto error_of = [&](const std::function<void()>& fn) {
    return std::string(testing::expect_input_error(fn).what());
  };
  SpeciesCloud c = cloud_;
  c.concentration_g_m3[0][7] = -1.0f;
  EXPECT_TRUE(contains(error_of([&] { write_species_keyframe(out, c, 1.0); }),
                       "concentration_000 voxel (7,0,0)"));
  c = cloud_;
  c.species[1].wavelengths_um[2] = 11.0;
  EXPECT_TRUE(contains(error_of([&] { write_species_keyframe(out, c, 1.0); }), "'soot'"));
  EXPECT_TRUE(contains(error_of([&] { write_species_keyframe(out, cloud_, -1.0); }), "time_s"));
  for (const char* key : {"obscura_form", "species_optics", "species_count", "concentration_units"})
    EXPECT_TRUE(contains(error_of([&] {
                           write_species_keyframe(out, cloud_, 1.0, {{key, "x"}});
                         }),
                         key));
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace obscura
