// `obscura validate`: every canonical case passes at its default sample count,
// a run too small to resolve its tolerance is reported as a failure with a
// non-zero exit, and bad parameters name their option.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

class ValidateTest : public testing::TempDirTest {};

TEST_F(ValidateTest, AllCasesPass) {
  const auto r = testing::run_cli("validate all --json", dir_);
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  const auto rows = nlohmann::json::parse(r.out);
  ASSERT_EQ(rows.size(), 10u);  // slab R, T, T_direct; furnace; …; 3 puff rays
  for (const auto& row : rows) {
    EXPECT_TRUE(row["pass"].get<bool>()) << row.dump();
    for (const char* key :
         {"case", "quantity", "reference", "obtained", "relative_error", "stderr"})
      EXPECT_TRUE(row.contains(key)) << key;
  }
}

TEST_F(ValidateTest, ParametersReachTheCase) {
  const auto r = testing::run_cli(
      "validate equilibrium --albedo 0.3 --tau 4 --g -0.5 --temperature 500 --json", dir_);
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  const auto rows = nlohmann::json::parse(r.out);
  EXPECT_NE(rows[0]["case"].get<std::string>().find("albedo=0.3 tau=4 g=-0.5 T=500"),
            std::string::npos);
  const auto t = testing::run_cli("validate emitting-slab --tau 0.1 --json", dir_);
  ASSERT_EQ(t.status, 0) << t.err;
  EXPECT_NEAR(nlohmann::json::parse(t.out)[0]["reference"].get<double>(), -std::expm1(-0.1), 1e-12);
}

TEST_F(ValidateTest, SlabPrintsItsFluxesAndItsReference) {
  const auto r = testing::run_cli(
      "validate slab --albedo 0.9 --tau 1 --g 0.5 --incidence diffuse --json", dir_);
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key :
       {"R", "T", "T_direct", "R_stderr", "T_stderr", "rows", "reference", "pass"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_DOUBLE_EQ(j["reference"]["R"].get<double>(), 0.227953106);  // DISORT row of the table
  EXPECT_NEAR(j["R"].get<double>(), 0.227953106,
              0.01 * 0.227953106 + 3 * j["R_stderr"].get<double>());
  EXPECT_TRUE(j["pass"].get<bool>());
  // No table row: obtained values, unjudged, exit 0.
  const auto u = testing::run_cli("validate slab --albedo 0.3 --tau 0.5 --samples 20000", dir_);
  EXPECT_EQ(u.status, 0) << u.out << u.err;
  EXPECT_NE(u.out.find("no reference"), std::string::npos) << u.out;
  // The reference table is an option, and a missing one is named.
  const auto m =
      testing::run_cli("validate slab --reference " + (dir_ / "none.csv").string(), dir_);
  EXPECT_EQ(m.status, 1);
  EXPECT_NE(m.err.find("none.csv"), std::string::npos) << m.err;
  const auto n = testing::run_cli("validate slab --mu0 0.5", dir_);
  EXPECT_EQ(n.status, 1);
  EXPECT_NE(n.err.find("--mu0"), std::string::npos) << n.err;
  EXPECT_NE(testing::run_cli("validate slab --incidence sideways", dir_).status, 0);
}

TEST_F(ValidateTest, TooFewSamplesFailWithNonZeroExit) {
  const auto r = testing::run_cli("validate single-scatter --samples 1000", dir_);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find("FAIL"), std::string::npos) << r.out;
}

TEST_F(ValidateTest, BadParametersAreNamed) {
  auto r = testing::run_cli("validate furnace --tau -1", dir_);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("--tau"), std::string::npos) << r.err;
  r = testing::run_cli("validate single-scatter --tau 0.5", dir_);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("--tau"), std::string::npos) << r.err;
  r = testing::run_cli("validate nonsense", dir_);
  EXPECT_NE(r.status, 0);
  r = testing::run_cli("validate furnace --samples 1", dir_);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("--samples"), std::string::npos) << r.err;
  r = testing::run_cli("validate slab --method radiance-cache --sh-degree 7", dir_);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("--sh-degree"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace obscura
