// `scripts/demo --quick` (CI's variant of `make demo`) run end to end: the
// preparation, the radiance-cache frames of four sensors over 30 s, metrics,
// plots and the contact sheet must exist and not be trivial — images that
// vary across pixels, and metrics that change with time as the screen builds
// up and drifts away.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "obscura/io/exr_writer.h"
#include "obscura/io/png_file.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

namespace fs = std::filesystem;

class DemoQuick : public testing::TempDirTest {};

// The CSV as rows of column → text.
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  for (std::stringstream ss(line); std::getline(ss, line, ',');) header.push_back(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::map<std::string, std::string> row;
    std::stringstream ss(line);
    std::string cell;
    for (const auto& h : header) {
      std::getline(ss, cell, ',');
      row[h] = cell;
    }
    rows.push_back(row);
  }
  return rows;
}

TEST_F(DemoQuick, ArtefactsExistAndAreNotTrivial) {
  const fs::path out = dir_ / "demo";
  const fs::path log = dir_ / "demo.log";
  const std::string command = std::string("OBSCURA='") + OBSCURA_CLI_PATH + "' OUT='" +
                              out.string() + "' '" + OBSCURA_SOURCE_DIR +
                              "/scripts/demo' --quick > '" + log.string() + "' 2>&1";
  const int rc = std::system(command.c_str());
  std::ifstream log_in(log);
  const std::string log_text((std::istreambuf_iterator<char>(log_in)),
                             std::istreambuf_iterator<char>());
  ASSERT_EQ(rc, 0) << log_text;

  const std::vector<std::string> sensors = {"tv", "laser", "mwir_seeker", "lwir_seeker"};
  for (const char* f :
       {"contact_sheet.png", "metrics.csv", "metrics.json", "metrics_transmittance.png",
        "metrics_screened_fraction.png", "metrics_contrast.png", "metrics_delta_t.png",
        "time_series.csv", "summary.json", "cloud/cloud.json"})
    EXPECT_TRUE(fs::is_regular_file(out / f)) << f << "\n" << log_text;
  for (const auto& s : sensors)
    EXPECT_TRUE(fs::is_regular_file(out / ("target_mask_" + s + ".png"))) << s;
  const PngSize sheet = read_png_size(out / "contact_sheet.png");
  EXPECT_GT(sheet.width, 300);
  EXPECT_GT(sheet.height, 200);

  // A frame at 6 s, when the screen stands: every sensor's images vary across pixels.
  for (const auto& s : sensors) {
    const ExrImage img = read_exr(out / (s + "_f0001.exr"));
    int channels = 0;
    for (const auto& [name, values] : img.channels) {
      const auto ends_with = [&](const std::string& suffix) {
        return name.size() > suffix.size() &&
               name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
      };
      if (!ends_with(".radiance") && !ends_with(".transmittance")) continue;
      const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
      EXPECT_LT(*lo, *hi) << s << " " << name << " is constant";
      ++channels;
    }
    EXPECT_EQ(channels, 2) << s;
  }

  // Metrics: 6 frames × 4 sensors; the target is seen clear at 0 s and
  // hidden later in the visible, and the screened fraction changes with time
  // for every sensor.
  const auto rows = read_csv(out / "metrics.csv");
  ASSERT_EQ(rows.size(), 24u);
  std::map<std::string, std::vector<double>> screened, transmittance;
  for (const auto& r : rows) {
    EXPECT_GT(std::stoi(r.at("target_pixels")), 10) << r.at("sensor");
    screened[r.at("sensor")].push_back(std::stod(r.at("screened_fraction")));
    transmittance[r.at("sensor")].push_back(std::stod(r.at("transmittance_mean")));
  }
  for (const auto& s : sensors) {
    ASSERT_EQ(transmittance[s].size(), 6u) << s;
    EXPECT_GT(transmittance[s].front(), 0.99) << s << ": no smoke at t = 0";
    const auto [lo, hi] = std::minmax_element(transmittance[s].begin(), transmittance[s].end());
    EXPECT_GT(*hi - *lo, 0.2) << s << ": transmittance does not change with time";
  }
  EXPECT_EQ(*std::max_element(screened["tv"].begin(), screened["tv"].end()), 1.0);
}

}  // namespace
}  // namespace obscura
