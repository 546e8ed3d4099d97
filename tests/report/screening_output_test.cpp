// Writing screening metrics (io/screening_output.h): the CSV and JSON with
// empty cells / nulls for undefined values, the plots, the mask PNG and the
// printed summary.
#include "obscura/report/screening_output.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "obscura/io/png_file.h"
#include "support/input_error.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Three frames of a visible and an LWIR band: the LWIR target is screened
// from 1.8 s; the visible band has no background (contrast undefined) at 0 s.
std::vector<ScreeningMetrics> rows() {
  std::vector<ScreeningMetrics> out;
  const double fractions[3] = {0.0, 0.5, 1.0};
  for (int f = 0; f < 3; ++f)
    for (const char* band : {"visible", "lwir"}) {
      ScreeningMetrics m;
      m.time_s = f;
      m.sensor = "cam";
      m.band = Band::preset(band);
      m.target_pixels = 40;
      m.background_pixels = 60;
      m.transmittance_mean = 1.0 - 0.45 * f;
      m.transmittance_p10 = 0.9 - 0.45 * f;
      m.transmittance_p50 = 1.0 - 0.45 * f;
      m.transmittance_p90 = 1.0 - 0.4 * f;
      m.screened_fraction = fractions[f];
      m.target_radiance = 10.0 - f;
      m.background_radiance = 8.0;
      m.contrast = (f == 0 && m.band.name() == "visible") ? kNaN : (m.target_radiance - 8.0) / 8.0;
      m.target_apparent_temperature_k = 300.0 - f;
      m.background_apparent_temperature_k = 295.0;
      m.delta_t_k = 5.0 - f;
      out.push_back(m);
    }
  return out;
}

TEST(ScreeningOutput, CsvHasUnitsInTheHeaderAndEmptyCellsForUndefinedValues) {
  const std::string csv = screening_metrics_csv(rows());
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 6);
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_EQ(header,
            "time_s,sensor,band,band_min_um,band_max_um,target_pixels,background_pixels,"
            "transmittance_mean,transmittance_p10,transmittance_p50,transmittance_p90,"
            "screened_fraction,target_radiance_W_m-2_sr-1,background_radiance_W_m-2_sr-1,contrast,"
            "target_apparent_temperature_K,background_apparent_temperature_K,delta_t_K");
  EXPECT_NE(csv.find("\n0,cam,visible,0.4,0.7,40,60,1,0.9,1,1,0,10,8,,300,295,5\n"),
            std::string::npos)
      << csv;
  EXPECT_NE(csv.find("\n2,cam,lwir,8,12,40,60,0.1,0,0.1,0.2,1,8,8,0,298,295,3\n"),
            std::string::npos)
      << csv;
}

TEST(ScreeningOutput, JsonHasNullsForUndefinedAndNotReached) {
  const auto r = rows();
  MetricsSettings settings;
  const auto series = summarize_screening(r, settings, 0.5);
  TargetMask mask;
  mask.sensor = "cam";
  mask.width = 4;
  mask.height = 2;
  mask.labels.assign(8, MaskLabel::kOther);
  finish_target_mask(mask, 8);
  const nlohmann::json j =
      screening_metrics_json({{"software", "obscura"}}, settings, 0.5, {mask}, r, series);
  EXPECT_EQ(j["settings"]["transmittance_threshold"], 0.05);
  EXPECT_EQ(j["settings"]["reference_time_s"], 0.5);
  ASSERT_EQ(j["frames"].size(), 6u);
  EXPECT_TRUE(j["frames"][0]["contrast"].is_null());
  EXPECT_EQ(j["frames"][1]["delta_t_k"], 5.0);
  EXPECT_TRUE(j["targets"][0]["target_bbox_px"].is_null());
  ASSERT_EQ(j["series"].size(), 2u);
  // Both bands share the screened fractions 0, 0.5, 1: 0.9 at 1.8 s.
  const auto& lwir = j["series"][1];
  EXPECT_EQ(lwir["band"], "lwir");
  EXPECT_DOUBLE_EQ(lwir["time_to_screen_s"].get<double>(), 1.3);
  EXPECT_DOUBLE_EQ(lwir["screening_duration_s"].get<double>(), 0.2);
  EXPECT_DOUBLE_EQ(lwir["screened_until_s"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(lwir["min_transmittance_mean"].get<double>(), 0.1);

  // Not reached: nulls, and a duration of 0.
  MetricsSettings strict = settings;
  strict.screened_fraction = 1.0;
  auto never = r;
  for (auto& m : never) m.screened_fraction = std::min(m.screened_fraction, 0.5);
  const nlohmann::json s = screening_series_json(summarize_screening(never, strict, 0.0));
  EXPECT_TRUE(s[0]["time_to_screen_s"].is_null());
  EXPECT_TRUE(s[0]["screened_from_s"].is_null());
  EXPECT_EQ(s[0]["screening_duration_s"], 0.0);
  EXPECT_TRUE(s[0]["screened_intervals_s"].empty());
}

TEST(ScreeningOutput, SummaryTextSaysWhenTheTargetIsNotScreened) {
  auto r = rows();
  for (auto& m : r)
    if (m.band.name() == "visible") m.screened_fraction = 0.25;
  const std::string text = screening_summary_text(summarize_screening(r, MetricsSettings{}, 0.5),
                                                  MetricsSettings{}, 0.5);
  EXPECT_NE(text.find("cam / lwir"), std::string::npos) << text;
  EXPECT_NE(text.find("time to screen 1.3 s, screened 0.2 s in all (first 1.8–2 s)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("cam / visible  not screened (max screened fraction 0.25)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("min mean transmittance 0.1 at t = 2 s"), std::string::npos) << text;
}

class ScreeningFiles : public testing::TempDirTest {};

TEST_F(ScreeningFiles, WritesTheFourPlots) {
  const auto files =
      write_screening_plots(dir_, rows(), MetricsSettings{}, R"({"software":"obscura"})");
  EXPECT_TRUE(files.skipped.empty());
  ASSERT_EQ(files.written.size(), 4u);
  for (const char* name : {kTransmittancePlot, kScreenedFractionPlot, kContrastPlot, kDeltaTPlot}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(std::filesystem::exists(dir_ / name));
    EXPECT_EQ(read_png_size(dir_ / name).width, 900);
    EXPECT_EQ(read_png_text_chunks(dir_ / name).count("obscura.provenance"), 1u);
  }
}

TEST_F(ScreeningFiles, SkipsPlotsWithoutAnEligibleBand) {
  auto r = rows();
  std::erase_if(r, [](const ScreeningMetrics& m) { return m.band.name() == "visible"; });
  const auto files = write_screening_plots(dir_, r, MetricsSettings{}, "");
  EXPECT_EQ(files.written.size(), 3u);
  ASSERT_EQ(files.skipped.size(), 1u);
  EXPECT_TRUE(testing::contains(files.skipped[0], "metrics_contrast.png: no visible/NIR band"))
      << files.skipped[0];
  EXPECT_FALSE(std::filesystem::exists(dir_ / kContrastPlot));
}

TEST_F(ScreeningFiles, MaskPngHasOnePixelPerSensorPixel) {
  TargetMask m;
  m.sensor = "cam";
  m.width = 30;
  m.height = 20;
  m.labels.assign(600, MaskLabel::kOther);
  m.labels[10 * 30 + 15] = MaskLabel::kTarget;
  finish_target_mask(m, 2);
  const auto path = dir_ / "target_mask_cam.png";
  write_target_mask_png(path, m, R"({"software":"obscura"})");
  const PngSize size = read_png_size(path);
  EXPECT_EQ(size.width, 30);
  EXPECT_EQ(size.height, 20);
  EXPECT_EQ(read_png_text_chunks(path).count("obscura.provenance"), 1u);
}

}  // namespace
}  // namespace obscura
