// `mpirun -np 2 obscura …` (docs/cluster.md): a sequence shared by frames and
// by tiles writes what one process writes, a study shares its cases and
// records a broken one, a failing frame is reported once by rank 0, and a
// command that does not share its work refuses to run on several ranks.
// Built only when the build has MPI and CMake found mpirun (the suite passes
// without them; these tests are then absent, not skipped).
#ifdef OBSCURA_TEST_MPIEXEC

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/puff_sequence.h"
#include "support/temp_dir_test.h"
#include "support/tiny_study.h"

namespace fs = std::filesystem;

namespace obscura {
namespace {

// Two ranks on whatever cores there are; root is allowed in CI containers.
std::string mpirun(int ranks) {
  return std::string(OBSCURA_TEST_MPIEXEC) + " --allow-run-as-root --oversubscribe -np " +
         std::to_string(ranks) + " " + OBSCURA_CLI_PATH + " ";
}

testing::CliResult run_mpi(int ranks, const std::string& args, const fs::path& scratch) {
  const auto out = scratch / "mpi_stdout.txt", err = scratch / "mpi_stderr.txt";
  const std::string cmd = mpirun(ranks) + args + " >" + out.string() + " 2>" + err.string();
  const int raw = std::system(cmd.c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, testing::read_text_file(out),
          testing::read_text_file(err)};
}

class MpiCliTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    testing::write_growing_puff(dir_);
    for (const char* method : {"emission-absorption", "radiance-cache"}) {
      nlohmann::json render = {{"method", method}, {"seed", 3}, {"spectral_nodes_per_band", 2}};
      if (std::string(method) == "radiance-cache") render["radiance_cache"] = {{"photons", 4000}};
      const nlohmann::json scene = testing::growing_puff_scene(render, 20, 13, {"mwir", "lwir"});
      std::ofstream(dir_ / (std::string(method) + ".json")) << scene.dump(2);
    }
  }

  std::string render_args(const std::string& method, const fs::path& out) const {
    return "render " + (dir_ / (method + ".json")).string() + " -o " + out.string() +
           " --time 0:3:1.5 --threads 1";
  }
};

TEST_F(MpiCliTest, FramesOnTwoRanksAreTheFramesOfOneProcess) {
  const auto one = testing::run_cli(render_args("emission-absorption", dir_ / "one"), dir_);
  ASSERT_EQ(one.status, 0) << one.err;
  const auto two = run_mpi(2, render_args("emission-absorption", dir_ / "two"), dir_);
  ASSERT_EQ(two.status, 0) << two.err;
  // Each frame was rendered once, by whichever rank drew it.
  for (const char* frame : {": frame 1/3 ", ": frame 2/3 ", ": frame 3/3 "}) {
    const auto at = two.err.find(frame);
    EXPECT_NE(at, std::string::npos) << frame << two.err;
    EXPECT_EQ(two.err.find(frame, at + 1), std::string::npos) << frame << two.err;
  }
  testing::expect_same_render_outputs(dir_ / "one", dir_ / "two");
}

TEST_F(MpiCliTest, TilesAndPhotonsOnTwoRanksAreTheFramesOfOneProcess) {
  const auto one = testing::run_cli(render_args("radiance-cache", dir_ / "one"), dir_);
  ASSERT_EQ(one.status, 0) << one.err;
  const auto two = run_mpi(2, render_args("radiance-cache", dir_ / "two") + " --share tiles", dir_);
  ASSERT_EQ(two.status, 0) << two.err;
  EXPECT_NE(two.err.find("rank 1/2: rows of frame 3/3"), std::string::npos) << two.err;
  testing::expect_same_render_outputs(dir_ / "one", dir_ / "two");
}

TEST_F(MpiCliTest, AFrameThatFailsIsReportedOnceAndTheFramesBeforeItAreKept) {
  fs::resize_file(dir_ / "k1.vdb", 100);
  const auto r = run_mpi(2, render_args("emission-absorption", dir_ / "out"), dir_);
  EXPECT_EQ(r.status, 1) << r.err;
  std::size_t errors = 0;
  for (std::size_t at = r.err.find("obscura: error"); at != std::string::npos;
       at = r.err.find("obscura: error", at + 1))
    ++errors;
  EXPECT_EQ(errors, 1u) << r.err;
  EXPECT_NE(r.err.find("k1.vdb"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "ir_f0000.exr"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "ir_f0001.exr"));
  const std::string summary = testing::read_text_file(dir_ / "out" / "summary.json");
  EXPECT_NE(summary.find("\"failed\""), std::string::npos) << summary;
}

TEST_F(MpiCliTest, AStudySharesItsCasesAndRecordsABrokenOne) {
  nlohmann::json study = testing::write_tiny_study(dir_);
  study["axes"][1]["values"] = {"B", "Q", "F"};
  std::ofstream(dir_ / "study.json") << study.dump(2);
  const std::string args = "study " + (dir_ / "study.json").string() + " --threads 1 -o ";
  const auto one = testing::run_cli(args + (dir_ / "one").string(), dir_);
  EXPECT_EQ(one.status, 3) << one.err;  // some cases failed; the table is complete
  const auto two = run_mpi(2, args + (dir_ / "two").string(), dir_);
  EXPECT_EQ(two.status, 3) << two.err;
  // Each rank takes the next free case: both ran some, one of them the broken one.
  EXPECT_NE(two.err.find("rank 0/2: case_"), std::string::npos) << two.err;
  EXPECT_NE(two.err.find("rank 1/2: case_"), std::string::npos) << two.err;
  EXPECT_NE(two.err.find("case_0001 2/6 (wind_from_deg=250, stability=Q) done"), std::string::npos)
      << two.err;
  EXPECT_NE(two.out.find("6 cases: 4 ok, 2 failed"), std::string::npos) << two.out;
  // The same table but for the wall times (column 6).
  const auto without_seconds = [](const std::string& csv) {
    std::string out, line;
    std::stringstream in(csv);
    while (std::getline(in, line)) {
      std::size_t at = 0;
      for (int c = 0; c < 5; ++c) at = line.find(',', at) + 1;
      out += line.substr(0, at) + line.substr(line.find(',', at)) + "\n";
    }
    return out;
  };
  const std::string a = testing::read_text_file(dir_ / "one" / "results.csv");
  EXPECT_EQ(std::count(a.begin(), a.end(), '\n'), 7);
  EXPECT_EQ(without_seconds(a),
            without_seconds(testing::read_text_file(dir_ / "two" / "results.csv")));
}

TEST_F(MpiCliTest, ACommandThatDoesNotShareItsWorkRefusesSeveralRanks) {
  const auto r = run_mpi(2, "validate furnace --method path-tracer", dir_);
  EXPECT_EQ(r.status, 64) << r.err;
  EXPECT_NE(r.err.find("'validate' runs on one process"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace obscura

#endif  // OBSCURA_TEST_MPIEXEC
