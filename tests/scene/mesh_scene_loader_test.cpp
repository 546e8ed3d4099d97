// Scene files with "mesh" and "heightfield" surfaces.
#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <map>

#include "obscura/scene/mesh_surface.h"
#include "obscura/scene/scene.h"
#include "support/input_error.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

using testing::contains;
using testing::expect_input_error;

constexpr double kInf = std::numeric_limits<double>::infinity();

// A unit cube "body" at the origin and a small cube "hot" in front of it (+y).
const char* kVehicleObj = R"(# two parts
g body
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
g hot
v 0.25 2 0
v 0.75 2 0
v 0.75 2.5 0
v 0.25 2.5 0
v 0.25 2 0.5
v 0.75 2 0.5
v 0.75 2.5 0.5
v 0.25 2.5 0.5
f 9 12 11 10
f 13 14 15 16
f 9 10 14 13
f 10 11 15 14
f 11 12 16 15
f 12 9 13 16
)";

class SceneLoaderMesh : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    std::ofstream(dir_ / "vehicle.obj") << kVehicleObj;
    std::ofstream(dir_ / "hills.csv") << "0,0,1\n0,1,2\n";
  }
  nlohmann::json scene(const nlohmann::json& surface) {
    nlohmann::json doc = nlohmann::json::parse(R"({
      "sensors": [{"name": "ir", "position": [0, -50, 5], "look_at": [0, 0, 0], "fov_deg": 30,
                   "width": 8, "height": 6, "bands": ["lwir"]}]})");
    doc["surfaces"] = nlohmann::json::array({surface});
    return doc;
  }
  nlohmann::json vehicle() {
    return nlohmann::json::parse(R"({"type": "mesh", "name": "veh", "file": "vehicle.obj",
      "position": [10, 20, 0], "heading_deg": 90, "scale": 2, "target": true,
      "temperature": 295, "emissivity": 0.9,
      "parts": {"hot": {"temperature": 340, "emissivity": [[3, 0.8], [10, 0.95]]}}})");
  }
  Scene load(const nlohmann::json& surface) {
    return parse_scene(scene(surface), dir_ / "scene.json");
  }
  InputError error(const nlohmann::json& surface) {
    const InputError e = expect_input_error([&] { load(surface); });
    return e;
  }
};

TEST_F(SceneLoaderMesh, OneSurfacePerPartWithItsMaterial) {
  const Scene s = load(vehicle());
  ASSERT_EQ(s.surfaces.size(), 2u);
  EXPECT_EQ(s.surfaces[0]->name(), "veh/body");
  EXPECT_EQ(s.surfaces[1]->name(), "veh/hot");
  EXPECT_EQ(s.surfaces[0]->material().temperature_k, 295);
  EXPECT_EQ(s.surfaces[0]->material().emissivity, 0.9);
  EXPECT_EQ(s.surfaces[1]->material().temperature_k, 340);
  EXPECT_EQ(s.surfaces[1]->material().emissivity_table.size(), 2u);
  EXPECT_TRUE(s.surfaces[0]->is_target());
  EXPECT_TRUE(s.surfaces[1]->is_target());
  EXPECT_FALSE(s.surfaces[0]->is_terrain());  // a vehicle is not ground
  EXPECT_EQ(s.input_files.back(), dir_ / "vehicle.obj");
}

// Scaled by 2, turned 90° counter-clockwise (+y to −x), moved to (10, 20, 0):
// the hot cube spans x 5..6, y 20.5..21.5, z 0..1.
TEST_F(SceneLoaderMesh, TransformedMeshIsHitWhereExpected) {
  const Scene s = load(vehicle());
  const auto* hot = dynamic_cast<const MeshSurface*>(s.surfaces[1].get());
  ASSERT_TRUE(hot);
  EXPECT_LT(length(hot->bounds().lo - Vec3(5, 20.5, 0)), 1e-12);
  EXPECT_LT(length(hot->bounds().hi - Vec3(6, 21.5, 1)), 1e-12);
  // Along +x at y = 21, z = 0.5: the hot cube's −x face at x = 5 comes first.
  SurfaceHit hit;
  ASSERT_TRUE(intersect_surfaces(s.surfaces, Ray{{-100, 21, 0.5}, {1, 0, 0}}, 0, kInf, hit));
  EXPECT_EQ(hit.surface, 1);
  EXPECT_NEAR(hit.t, 105.0, 1e-9);
  EXPECT_LT(length(hit.normal - Vec3(-1, 0, 0)), 1e-12);
  // Beside it, the body (x 8..10, y 20..22, z 0..2).
  ASSERT_TRUE(intersect_surfaces(s.surfaces, Ray{{-100, 20.2, 0.5}, {1, 0, 0}}, 0, kInf, hit));
  EXPECT_EQ(hit.surface, 0);
  EXPECT_NEAR(hit.t, 108.0, 1e-9);
  EXPECT_LT(length(hit.normal - Vec3(-1, 0, 0)), 1e-12);
}

TEST_F(SceneLoaderMesh, DefaultsAndEveryPartCovered) {
  nlohmann::json v = {{"type", "mesh"}, {"file", "vehicle.obj"}, {"temperature", 300}};
  const Scene s = load(v);
  ASSERT_EQ(s.surfaces.size(), 2u);
  EXPECT_EQ(s.surfaces[0]->name(), "mesh0/body");
  EXPECT_EQ(s.surfaces[1]->material().emissivity, 1.0);
  EXPECT_FALSE(s.surfaces[0]->is_target());
  // No default, but every part has an entry: fine.
  v.erase("temperature");
  v["parts"] = {{"body", {{"temperature", 280}}}, {"hot", {{"temperature", 350}}}};
  EXPECT_EQ(load(v).surfaces[1]->material().temperature_k, 350);
}

TEST_F(SceneLoaderMesh, UnknownPartListsThePartsPresent) {
  nlohmann::json v = vehicle();
  v["parts"]["turet"] = {{"temperature", 300}};
  const InputError e = error(v);
  EXPECT_EQ(e.file(), (dir_ / "scene.json").string());
  EXPECT_EQ(e.field(), "/surfaces/0/parts/turet");
  EXPECT_TRUE(contains(e.detail(), "no part 'turet'")) << e.what();
  EXPECT_TRUE(contains(e.detail(), "body, hot")) << e.what();
}

TEST_F(SceneLoaderMesh, BadMeshEntries) {
  nlohmann::json v = vehicle();
  v.erase("temperature");
  v.erase("emissivity");
  InputError e = error(v);
  EXPECT_EQ(e.field(), "/surfaces/0/temperature");
  EXPECT_TRUE(contains(e.detail(), "part 'body' has no material")) << e.what();

  v = vehicle();
  v["parts"]["hot"]["emisivity"] = 0.5;
  EXPECT_EQ(error(v).field(), "/surfaces/0/parts/hot/emisivity");
  v = vehicle();
  v["parts"]["hot"]["emissivity"] = 1.5;
  EXPECT_EQ(error(v).field(), "/surfaces/0/parts/hot/emissivity");
  v = vehicle();
  v["scale"] = 0;
  EXPECT_EQ(error(v).field(), "/surfaces/0/scale");
  v = vehicle();
  v["heading"] = 10;
  EXPECT_EQ(error(v).field(), "/surfaces/0/heading");
  v = vehicle();
  v["file"] = "nothere.obj";
  e = error(v);
  EXPECT_EQ(e.field(), "/surfaces/0/file");
  EXPECT_TRUE(contains(e.detail(), "no such file")) << e.what();
  // An error inside the OBJ names the OBJ and its line.
  std::ofstream(dir_ / "broken.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n";
  v["file"] = "broken.obj";
  e = error(v);
  EXPECT_EQ(e.file(), (dir_ / "broken.obj").string());
  EXPECT_EQ(e.field(), "line 4");
}

TEST_F(SceneLoaderMesh, Heightfield) {
  const nlohmann::json h = nlohmann::json::parse(R"({"type": "heightfield", "name": "terrain",
      "file": "hills.csv", "origin": [100, 200], "spacing_m": 10, "temperature": 290, "emissivity": 0.95})");
  const Scene s = load(h);
  ASSERT_EQ(s.surfaces.size(), 1u);
  EXPECT_EQ(s.surfaces[0]->name(), "terrain");
  EXPECT_EQ(s.surfaces[0]->material().emissivity, 0.95);
  EXPECT_TRUE(s.surfaces[0]->is_terrain());  // the radiance cache's ground light covers it
  // Straight down onto sample (row 1, column 2) = (120, 210), height 2.
  SurfaceHit hit;
  ASSERT_TRUE(s.surfaces[0]->intersect(Ray{{120, 210, 50}, {0, 0, -1}}, 0, kInf, hit));
  EXPECT_NEAR(hit.t, 48.0, 1e-9);
  // Outside the grid there is no ground.
  EXPECT_FALSE(s.surfaces[0]->intersect(Ray{{90, 210, 50}, {0, 0, -1}}, 0, kInf, hit));
  EXPECT_EQ(s.input_files.back(), dir_ / "hills.csv");
}

TEST_F(SceneLoaderMesh, BadHeightfieldEntries) {
  const nlohmann::json good = nlohmann::json::parse(R"({"type": "heightfield", "file": "hills.csv",
      "origin": [0, 0], "spacing_m": 10, "temperature": 290})");
  nlohmann::json h = good;
  h["origin"] = {1, 2, 3};
  EXPECT_EQ(error(h).field(), "/surfaces/0/origin");
  h = good;
  h["spacing_m"] = -1;
  EXPECT_EQ(error(h).field(), "/surfaces/0/spacing_m");
  h = good;
  h.erase("spacing_m");
  EXPECT_EQ(error(h).field(), "/surfaces/0/spacing_m");
  h = good;
  h.erase("temperature");
  EXPECT_EQ(error(h).field(), "/surfaces/0/temperature");
  h = good;
  h["parts"] = nlohmann::json::object();
  EXPECT_EQ(error(h).field(), "/surfaces/0/parts");
  std::ofstream(dir_ / "ragged.csv") << "1,2\n3\n";
  h = good;
  h["file"] = "ragged.csv";
  const InputError e = error(h);
  EXPECT_EQ(e.file(), (dir_ / "ragged.csv").string());
  EXPECT_EQ(e.field(), "line 2");
}

TEST_F(SceneLoaderMesh, UnknownTypeListsEveryType) {
  const InputError e = error({{"type", "sphere"}, {"temperature", 300}});
  EXPECT_TRUE(contains(e.detail(), "expected ground, box, mesh or heightfield")) << e.what();
}

TEST_F(SceneLoaderMesh, TheTankExampleLoads) {
  const Scene s =
      load_scene(std::filesystem::path(OBSCURA_SOURCE_DIR) / "examples" / "tank" / "scene.json");
  ASSERT_EQ(s.surfaces.size(), 6u);
  EXPECT_EQ(s.surfaces[0]->name(), "terrain");
  EXPECT_FALSE(s.surfaces[0]->is_target());
  std::map<std::string, double> temperature;
  for (std::size_t i = 1; i < s.surfaces.size(); ++i) {
    EXPECT_TRUE(s.surfaces[i]->is_target());
    temperature[s.surfaces[i]->name()] = s.surfaces[i]->material().temperature_k;
  }
  EXPECT_EQ(temperature, (std::map<std::string, double>{{"tank/hull", 293},
                                                        {"tank/turret", 293},
                                                        {"tank/gun", 300},
                                                        {"tank/tracks", 310},
                                                        {"tank/engine_deck", 340}}));
  // The camera sees the tank: its look-at ray hits a tank part first.
  SurfaceHit hit;
  const Vec3 eye(0, 300, 10);
  ASSERT_TRUE(
      intersect_surfaces(s.surfaces, Ray{eye, normalize(Vec3(0, 0, 1.2) - eye)}, 0, kInf, hit));
  EXPECT_GE(hit.surface, 1);
}

}  // namespace
}  // namespace obscura
