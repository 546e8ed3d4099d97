// Parameter studies (study/): the cases a study file makes, its errors, a
// study prepared, rendered and measured with one broken case recorded, a
// resumed study that runs only what is missing, and the same table whatever
// the number of processes.
#include <gtest/gtest.h>
#include <netcdf.h>

#include <cmath>
#include <fstream>
#include <mutex>

#include "obscura/io/json_reader.h"
#include "obscura/study/study_runner.h"
#include "obscura/study/study_spec.h"
#include "obscura/study/study_table.h"
#include "support/input_error.h"
#include "support/temp_dir_test.h"
#include "support/thread_process_group.h"
#include "support/tiny_study.h"

namespace fs = std::filesystem;

namespace obscura {
namespace {

// `fn` throws an InputError whose file ends with `file`, whose field is
// `field` and whose message contains `detail`.
void expect_error(const std::function<void()>& fn, const std::string& file,
                  const std::string& field, const std::string& detail) {
  const InputError e = testing::expect_input_error(fn);
  EXPECT_TRUE(e.file().ends_with(file)) << e.what();
  EXPECT_EQ(e.field(), field) << e.what();
  EXPECT_NE(e.detail().find(detail), std::string::npos) << e.what();
}
#define EXPECT_INPUT_ERROR(expr, file, field, detail) \
  expect_error([&] { (void)(expr); }, file, field, detail)

class StudyTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    study_ = testing::write_tiny_study(dir_);
  }

  void write(const std::string& name, const nlohmann::json& doc) const {
    std::ofstream(dir_ / name) << doc.dump(2);
  }
  StudySpec spec() const {
    write("study.json", study_);
    return load_study(dir_ / "study.json");
  }
  static const CaseSeries& lwir(const CaseResult& r) {
    EXPECT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.series.size(), 1u);
    return r.series.at(0);
  }

  nlohmann::json study_;
};

TEST_F(StudyTest, AGridMakesEveryCombinationWithTheLastAxisFastest) {
  const StudySpec s = spec();
  ASSERT_EQ(s.case_count, 4u);
  const StudyCase c = study_case(s, 1);
  EXPECT_EQ(c.id, "case_0001");
  EXPECT_EQ(describe_case(s, c), "wind_from_deg=250, stability=F");
  const CaseDocuments d = case_documents(s, study_case(s, 2), dir_ / "c2" / "cloud.json");
  EXPECT_EQ(d.prepare["dispersion"]["wind"]["from_deg"], 290);
  EXPECT_EQ(d.prepare["dispersion"]["stability"], "B");
  EXPECT_EQ(d.scene["clouds"][0]["manifest"], fs::absolute(dir_ / "c2" / "cloud.json").string());
  EXPECT_NE(d.fingerprint, case_documents(s, study_case(s, 1), dir_ / "c2").fingerprint);
}

TEST_F(StudyTest, ZipTakesTheAxesSideBySide) {
  study_["combine"] = "zip";
  const StudySpec s = spec();
  ASSERT_EQ(s.case_count, 2u);
  EXPECT_EQ(describe_case(s, study_case(s, 1)), "wind_from_deg=290, stability=F");
  study_["axes"][1]["values"] = {"B", "D", "F"};
  EXPECT_INPUT_ERROR(spec(), "study.json", "/axes/1/values", "needs 2");
}

TEST_F(StudyTest, BadStudiesAreErrorsNamingTheField) {
  nlohmann::json base = study_;
  study_["axes"][0]["path"] = "/dispersion/wind/from_degrees";
  EXPECT_INPUT_ERROR(spec(), "study.json", "/axes/0/path", "is not a value of");
  study_ = base;
  study_["axes"][1]["name"] = "wind_from_deg";
  EXPECT_INPUT_ERROR(spec(), "study.json", "/axes/1/name", "names two axes");
  study_ = base;
  study_["axes"][0]["values"] = nlohmann::json::array();
  EXPECT_INPUT_ERROR(spec(), "study.json", "/axes/0/values", "at least one");
  study_ = base;
  study_["axes"][0]["name"] = "wind direction";
  EXPECT_INPUT_ERROR(spec(), "study.json", "/axes/0/name", "letters, digits");
  study_ = base;
  study_["frames"] = 3;
  EXPECT_INPUT_ERROR(spec(), "study.json", "/frames", "");
  study_ = base;
  study_.erase("prepare");
  EXPECT_INPUT_ERROR(spec(), "study.json", "/axes/0/file", "no \"prepare\"");
  study_ = base;
  nlohmann::json scene = read_json_file((dir_ / "scene.json").string());
  scene["surfaces"][1]["target"] = false;
  write("scene.json", scene);
  EXPECT_INPUT_ERROR(spec(), "scene.json", "/surfaces", "no surface is a target");
}

TEST_F(StudyTest, EveryCaseIsPreparedRenderedAndMeasuredAndABrokenOneIsRecorded) {
  study_["axes"][1]["values"] = {"B", "Q", "F"};
  const StudySpec s = spec();
  const StudyResult r = run_study(s, dir_ / "out");
  ASSERT_EQ(r.cases.size(), 6u);
  EXPECT_EQ(r.failed, 2u);
  for (std::size_t i : {1u, 4u}) {
    EXPECT_FALSE(r.cases[i].ok);
    EXPECT_NE(r.cases[i].error.find("/dispersion/stability"), std::string::npos)
        << r.cases[i].error;
  }
  // Stable air (F) keeps the smoke together: the tank stays hidden longer
  // than in unstable air (B), for either wind.
  for (std::size_t wind : {0u, 3u}) {
    const CaseSeries &b = lwir(r.cases[wind]), &f = lwir(r.cases[wind + 2]);
    ASSERT_TRUE(b.screening_duration_s && f.screening_duration_s);
    EXPECT_GT(*f.screening_duration_s, *b.screening_duration_s + 1.0);
    EXPECT_LT(f.min_transmittance, b.min_transmittance);
  }
  for (std::size_t i = 0; i < 6; ++i)
    EXPECT_TRUE(fs::exists(dir_ / "out" / "cases" / study_case(s, i).id / "result.json"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "cases" / "case_0000" / "cloud")) << "clouds removed";
  const std::string csv = study_results_csv(s, r);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 7);
  EXPECT_NE(csv.find("case,id,status,wind_from_deg,stability,seconds,seeker_lwir_time_to_screen_s"),
            std::string::npos)
      << csv;
  EXPECT_NE(csv.find("1,case_0001,failed,250,Q,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\"\"Q\"\""), std::string::npos) << "quotes in the error doubled: " << csv;
  EXPECT_INPUT_ERROR(run_study(s, dir_ / "out"), "out", "", "--resume");

  // The table as NetCDF-CF, read back with the netCDF library.
  Provenance provenance;
  provenance.command_line = "obscura study study.json";
  write_study_results(s, r, dir_ / "out", provenance);
  int nc = -1;
  ASSERT_EQ(nc_open((dir_ / "out" / "results.nc").c_str(), NC_NOWRITE, &nc), NC_NOERR);
  int var = -1;
  ASSERT_EQ(nc_inq_varid(nc, "seeker_lwir_screening_duration_s", &var), NC_NOERR);
  std::vector<double> duration(6);
  ASSERT_EQ(nc_get_var_double(nc, var, duration.data()), NC_NOERR);
  char units[8] = {};
  ASSERT_EQ(nc_get_att_text(nc, var, "units", units), NC_NOERR);
  EXPECT_STREQ(units, "s");
  for (std::size_t i = 0; i < 6; ++i) {
    if (r.cases[i].ok)
      EXPECT_EQ(duration[i], *lwir(r.cases[i]).screening_duration_s) << i;
    else
      EXPECT_TRUE(std::isnan(duration[i])) << "failed case " << i << " is NaN";
  }
  ASSERT_EQ(nc_inq_varid(nc, "stability", &var), NC_NOERR);
  std::vector<char*> stability(6);
  ASSERT_EQ(nc_get_var_string(nc, var, stability.data()), NC_NOERR);
  EXPECT_STREQ(stability[1], "Q");
  nc_free_string(6, stability.data());
  ASSERT_EQ(nc_inq_varid(nc, "wind_from_deg", &var), NC_NOERR);
  std::vector<double> wind(6);
  ASSERT_EQ(nc_get_var_double(nc, var, wind.data()), NC_NOERR);
  EXPECT_EQ(wind, (std::vector<double>{250, 250, 250, 290, 290, 290}));
  nc_close(nc);
}

TEST_F(StudyTest, AResumedStudyRunsOnlyTheCasesWithoutACompleteResult) {
  const StudySpec s = spec();
  const StudyResult first = run_study(s, dir_ / "out");
  ASSERT_EQ(first.failed, 0u);
  // An interrupted run: one case never finished, one result is from other files.
  fs::remove(dir_ / "out" / "cases" / "case_0002" / "result.json");
  const fs::path stale = dir_ / "out" / "cases" / "case_0003" / "result.json";
  nlohmann::json j = read_json_file(stale.string());
  j["fingerprint"] = "0";
  std::ofstream(stale) << j.dump();
  StudyOptions options;
  options.resume = true;
  const StudyResult resumed = run_study(s, dir_ / "out", options);
  ASSERT_EQ(resumed.cases.size(), 4u);
  EXPECT_EQ(resumed.resumed, 2u);
  EXPECT_TRUE(resumed.cases[0].resumed && resumed.cases[1].resumed);
  EXPECT_FALSE(resumed.cases[2].resumed || resumed.cases[3].resumed);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(lwir(resumed.cases[i]).screening_duration_s,
              lwir(first.cases[i]).screening_duration_s);
    EXPECT_EQ(lwir(resumed.cases[i]).min_transmittance, lwir(first.cases[i]).min_transmittance);
  }
}

TEST_F(StudyTest, CasesSharedAmongRanksGiveTheSameTable) {
  const StudySpec s = spec();
  const StudyResult alone = run_study(s, dir_ / "alone");
  std::mutex m;
  StudyResult shared;
  testing::run_ranks(3, [&](const ProcessGroup& g) {
    StudyOptions options;
    options.processes = &g;
    options.threads = 1;
    StudyResult r = run_study(s, dir_ / "shared", options);
    std::lock_guard lock(m);
    if (g.is_root())
      shared = std::move(r);
    else
      EXPECT_TRUE(r.cases.empty());
  });
  ASSERT_EQ(shared.cases.size(), alone.cases.size());
  for (std::size_t i = 0; i < alone.cases.size(); ++i) {
    EXPECT_TRUE(shared.cases[i].rank >= 0 && shared.cases[i].rank < 3);
    EXPECT_EQ(lwir(shared.cases[i]).time_to_screen_s, lwir(alone.cases[i]).time_to_screen_s);
    EXPECT_EQ(lwir(shared.cases[i]).screening_duration_s,
              lwir(alone.cases[i]).screening_duration_s);
    EXPECT_EQ(lwir(shared.cases[i]).min_transmittance, lwir(alone.cases[i]).min_transmittance);
  }
}

}  // namespace
}  // namespace obscura
