#include "obscura/prep/dispersion/dispersion_config.h"

#include <gtest/gtest.h>

#include <functional>

#include "obscura/core/error.h"

namespace obscura {
namespace {

const char* kExample = R"({
  "dispersion": {
    "stability": "E",
    "sigma_set": "briggs-open-country",
    "ambient_temperature_k": 281.5,
    "wind": {"speed_m_s": 4.5, "from_deg": 270, "reference_height_m": 8},
    "devices": [
      {"name": "left", "position_m": [10, 20], "agent_mass_g": 360},
      {"position_m": [-3.5, 0], "release_height_m": 2, "start_s": 0.5, "burn_time_s": 25,
       "agent_mass_g": 500, "yield_factor": 4, "initial_sigma_m": 1.5,
       "source_temperature_excess_k": 60, "temperature_decay_time_s": 6,
       "puffs_per_second": 4},
      {"position_m": [0, -4], "agent_mass_g": 100}
    ]
  }
})";

DispersionConfig parse(const nlohmann::json& doc) {
  JsonObject root(doc, "scenario.json", "");
  DispersionConfig c = parse_dispersion_config(root.object("dispersion"));
  root.finish();
  return c;
}

// Parses kExample after `edit` and returns "file|field|detail" of the error.
std::string error_of(const std::function<void(nlohmann::json&)>& edit) {
  nlohmann::json doc = nlohmann::json::parse(kExample);
  edit(doc["dispersion"]);
  try {
    parse(doc);
  } catch (const InputError& e) {
    return e.file() + "|" + e.field() + "|" + e.detail();
  }
  return "no error";
}

TEST(DispersionConfig, ReadsEveryFieldAndFillsDefaults) {
  const DispersionConfig c = parse(nlohmann::json::parse(kExample));
  EXPECT_EQ(c.source, "scenario.json");
  EXPECT_EQ(c.stability, StabilityClass::kE);
  EXPECT_EQ(c.sigma_set, SigmaSet::kBriggsOpenCountry);
  EXPECT_EQ(c.ambient_temperature_k, 281.5);
  EXPECT_EQ(c.wind.speed_m_s, 4.5);
  EXPECT_EQ(c.wind.from_deg, 270);
  EXPECT_EQ(c.wind.reference_height_m, 8);
  EXPECT_EQ(c.wind.power_law_exponent, 0.35);  // class E rural default (docs/domain.md §3.6)
  EXPECT_EQ(c.wind.minimum_height_m, 1.0);
  ASSERT_EQ(c.devices.size(), 3u);
  const SmokeDevice& a = c.devices[0];
  EXPECT_EQ(a.name, "left");
  EXPECT_EQ(a.x_m, 10);
  EXPECT_EQ(a.y_m, 20);
  EXPECT_EQ(a.release_height_m, 0);
  EXPECT_EQ(a.start_s, 0);
  EXPECT_EQ(a.burn_time_s, 0);
  EXPECT_EQ(a.yield_factor, 1);
  EXPECT_EQ(a.initial_sigma_m, 1);
  EXPECT_EQ(a.source_temperature_excess_k, 0);
  EXPECT_EQ(a.puffs_per_second, 10);
  const SmokeDevice& b = c.devices[1];
  EXPECT_EQ(b.name, "device 1");
  EXPECT_EQ(b.release_height_m, 2);
  EXPECT_EQ(b.start_s, 0.5);
  EXPECT_EQ(b.burn_time_s, 25);
  EXPECT_EQ(b.agent_mass_g, 500);
  EXPECT_EQ(b.yield_factor, 4);
  EXPECT_EQ(b.initial_sigma_m, 1.5);
  EXPECT_EQ(b.source_temperature_excess_k, 60);
  EXPECT_EQ(b.temperature_decay_time_s, 6);
  EXPECT_EQ(b.puffs_per_second, 4);
  EXPECT_EQ(b.released_mass_g(), 2000);
}

TEST(DispersionConfig, DefaultsWhenOptionalTopLevelKeysAreAbsent) {
  nlohmann::json doc = nlohmann::json::parse(kExample);
  doc["dispersion"].erase("stability");
  doc["dispersion"].erase("sigma_set");
  doc["dispersion"].erase("ambient_temperature_k");
  doc["dispersion"]["wind"]["power_law_exponent"] = 0.0;
  const DispersionConfig c = parse(doc);
  EXPECT_EQ(c.stability, StabilityClass::kD);
  EXPECT_EQ(c.sigma_set, SigmaSet::kCcpsPuff);
  EXPECT_EQ(c.ambient_temperature_k, 288.15);
  EXPECT_EQ(c.wind.power_law_exponent, 0.0);  // explicit value wins over the class default
}

TEST(DispersionConfig, ErrorsNameTheFileAndJsonPath) {
  EXPECT_EQ(error_of([](auto& d) { d["devices"][2]["agent_mass_g"] = -5; }),
            "scenario.json|/dispersion/devices/2/agent_mass_g|expected a number > 0 g, found -5");
  EXPECT_EQ(error_of([](auto& d) { d["devices"][2].erase("agent_mass_g"); }),
            "scenario.json|/dispersion/devices/2/agent_mass_g|missing required field");
  EXPECT_EQ(error_of([](auto& d) { d["devices"][1]["yield_factor"] = "four"; }),
            "scenario.json|/dispersion/devices/1/yield_factor|expected a number, found string");
  EXPECT_EQ(error_of([](auto& d) { d["wind"]["speed_m_s"] = 0; }),
            "scenario.json|/dispersion/wind/speed_m_s|expected a number > 0 m/s, found 0");
  EXPECT_EQ(
      error_of([](auto& d) { d["wind"]["power_law_exponent"] = 1.5; }),
      "scenario.json|/dispersion/wind/power_law_exponent|expected a number in [0, 1], found 1.5");
  EXPECT_EQ(error_of([](auto& d) { d["devices"][0]["burn_time_s"] = -1; }),
            "scenario.json|/dispersion/devices/0/burn_time_s|expected a number >= 0 s, found -1");
  EXPECT_EQ(error_of([](auto& d) { d["devices"][1]["temperature_decay_time_s"] = 0; }),
            "scenario.json|/dispersion/devices/1/temperature_decay_time_s|expected a number > 0 s, "
            "found 0");
}

TEST(DispersionConfig, RejectsUnknownKeysAtEveryLevel) {
  for (const auto& [edit, path] :
       std::vector<std::pair<std::function<void(nlohmann::json&)>, std::string>>{
           {[](auto& d) { d["devices"][1]["agent_mas_g"] = 3; },
            "/dispersion/devices/1/agent_mas_g"},
           {[](auto& d) { d["wind"]["direction_deg"] = 3; }, "/dispersion/wind/direction_deg"},
           {[](auto& d) { d["mixing_height_m"] = 300; }, "/dispersion/mixing_height_m"}}) {
    const std::string e = error_of(edit);
    EXPECT_NE(e.find("|" + path + "|unknown field"), std::string::npos) << e;
  }
}

TEST(DispersionConfig, RejectsBadEnumsPositionsAndEmptyDeviceLists) {
  std::string e = error_of([](auto& d) { d["stability"] = "G"; });
  EXPECT_NE(e.find("|/dispersion/stability|unknown stability class \"G\""), std::string::npos) << e;
  e = error_of([](auto& d) { d["sigma_set"] = "pasquill"; });
  EXPECT_NE(e.find("|/dispersion/sigma_set|unknown sigma set"), std::string::npos) << e;
  e = error_of([](auto& d) { d["devices"][2]["position_m"] = {1, 2, 3}; });
  EXPECT_NE(e.find("|/dispersion/devices/2/position_m|expected 2 numbers"), std::string::npos) << e;
  e = error_of([](auto& d) { d["devices"] = nlohmann::json::array(); });
  EXPECT_NE(e.find("|/dispersion/devices|expected at least one"), std::string::npos) << e;
  e = error_of([](auto& d) { d["devices"][0]["source_temperature_excess_k"] = -300; });
  EXPECT_NE(e.find("|/dispersion/devices/0/source_temperature_excess_k|"), std::string::npos) << e;
  e = error_of([](auto& d) {
    d["devices"][1]["burn_time_s"] = 1e6;
    d["devices"][1]["puffs_per_second"] = 100;
  });
  EXPECT_NE(e.find("|/dispersion/devices/1/puffs_per_second|"), std::string::npos) << e;
  e = error_of([](auto& d) { d.erase("wind"); });
  EXPECT_EQ(e, "scenario.json|/dispersion/wind|missing required field");
}

}  // namespace
}  // namespace obscura
