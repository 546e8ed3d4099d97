// `obscura optics`: the list of shipped materials, a material at four band
// centres as JSON (keys, sources, unknowns as null), humidity, a user's own
// file, and bad input (exit status 1, the option or material named).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "support/cli_runner.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

class OpticsCliTest : public testing::TempDirTest {
 protected:
  testing::CliResult run(const std::string& args) {
    return testing::run_cli("optics " + args, dir_);
  }
};

TEST_F(OpticsCliTest, ListsTheShippedMaterials) {
  const auto r = run("--list");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* name : {"water_fog", "soot", "graphite_flakes", "brass_flakes",
                           "phosphorus_smoke", "fog_oil", "hc_smoke", "aluminium_flakes"})
    EXPECT_NE(r.out.find(name), std::string::npos) << name;
  const auto j = run("--list --json");
  ASSERT_EQ(j.status, 0) << j.err;
  const auto list = nlohmann::json::parse(j.out);
  ASSERT_GE(list.size(), 8u);
  for (const auto& e : list)
    for (const char* key : {"name", "kind", "description", "file"})
      EXPECT_TRUE(e.contains(key)) << key;
}

TEST_F(OpticsCliTest, FourBandCentresAsJson) {
  const auto r = run("--material phosphorus_smoke --wavelengths 0.55,1.064,4,10 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"material", "kind", "description", "file", "mass_basis",
                          "relative_humidity", "notes", "rows", "sources", "tabulated_note"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["material"], "phosphorus_smoke");
  ASSERT_EQ(j["rows"].size(), 4u);
  std::set<std::string> keys;
  for (const auto& [k, v] : j["rows"][0].items()) keys.insert(k);
  EXPECT_EQ(keys, (std::set<std::string>{"wavelength_um", "mass_extinction_m2_g",
                                         "mass_extinction_range_m2_g", "mass_scattering_m2_g",
                                         "mass_absorption_m2_g", "single_scattering_albedo",
                                         "asymmetry", "hydrated_mass_factor", "method", "note"}));
  EXPECT_EQ(j["rows"][0]["wavelength_um"].get<double>(), 0.55);
  EXPECT_EQ(j["rows"][0]["method"], "mie");
  // docs/domain.md §2.2: WP/RP 3–5 m²/g in the visible [U]; 0.2–0.5 in the LWIR [U].
  const double visible = j["rows"][0]["mass_extinction_m2_g"].get<double>();
  EXPECT_GT(visible, 3.0);
  EXPECT_LT(visible, 5.0);
  EXPECT_EQ(j["rows"][3]["method"], "tabulated");
  EXPECT_EQ(j["rows"][3]["mass_extinction_range_m2_g"], nlohmann::json({0.2, 0.5}));
  EXPECT_TRUE(j["rows"][3]["single_scattering_albedo"].is_null());  // not given by the source
  EXPECT_GE(j["sources"].size(), 5u);
  for (const auto& s : j["sources"]) EXPECT_FALSE(s["source"].get<std::string>().empty());
}

TEST_F(OpticsCliTest, TextTableHasUnitsAndSources) {
  const auto r = run("--material soot --wavelengths 0.55,10");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* s : {"µm", "m²/g", "albedo", "sources:", "Querry", "mass basis"})
    EXPECT_NE(r.out.find(s), std::string::npos) << s << "\n" << r.out;
}

TEST_F(OpticsCliTest, HumidityGrowsPhosphorusSmoke) {
  auto extinction = [&](const std::string& rh) {
    const auto r = run("--material phosphorus_smoke --wavelengths 0.55 --json --humidity " + rh);
    EXPECT_EQ(r.status, 0) << r.err;
    return nlohmann::json::parse(r.out)["rows"][0];
  };
  const auto dry = extinction("0"), wet = extinction("0.9");
  EXPECT_GT(wet["mass_extinction_m2_g"].get<double>(), dry["mass_extinction_m2_g"].get<double>());
  EXPECT_GT(wet["hydrated_mass_factor"].get<double>(), 1.0);
  EXPECT_EQ(dry["hydrated_mass_factor"].get<double>(), 1.0);
}

TEST_F(OpticsCliTest, UsersOwnFile) {
  const auto path = dir_ / "my_smoke.json";
  std::ofstream(path) << R"({"name": "my_smoke", "description": "d", "kind": "thin-flake",
    "mass_basis": "b", "flake": {"thickness_um": 0.25, "density_g_cm3": 2.0, "source": "mine"}})";
  const auto r = run("--material " + path.string() + " --wavelengths 1 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(r.out)["rows"][0]["mass_extinction_m2_g"].get<double>(),
                   2.0);
}

TEST_F(OpticsCliTest, BadInputIsNamed) {
  auto r = run("--material no_such_smoke --wavelengths 0.55");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("no_such_smoke"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--material"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;

  r = run("--material soot --wavelengths 0.55,abc");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--wavelengths"), std::string::npos) << r.err;

  r = run("--material soot --wavelengths 0.55,-1");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--wavelengths"), std::string::npos) << r.err;

  r = run("--material soot --wavelengths 0.55 --humidity 80");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--humidity"), std::string::npos) << r.err;

  r = run("--material soot");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--wavelengths"), std::string::npos) << r.err;

  r = run("--wavelengths 0.55");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--material"), std::string::npos) << r.err;

  // No data at the wavelength: the material file and the wavelength are named.
  r = run("--material aluminium_flakes --wavelengths 0.55,4");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("aluminium_flakes.json"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("0.55"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;

  // A broken user file: file and JSON path.
  const auto path = dir_ / "broken.json";
  std::ofstream(path) << R"({"name": "b", "description": "d", "kind": "thin-flake",
    "mass_basis": "b", "flake": {"thickness_um": 0.25, "density_g_cm3": 2.0, "source": "s",
    "colour": "gold"}})";
  r = run("--material " + path.string() + " --wavelengths 1");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("broken.json: /flake/colour"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace obscura
