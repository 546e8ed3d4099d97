// Temporaries of killed runs (io/stale_temporaries.h): which names are
// temporaries, and that only those of runs no longer alive are removed.
#include "obscura/io/stale_temporaries.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include "obscura/io/atomic_file.h"
#include "support/temp_dir_test.h"

namespace fs = std::filesystem;

namespace obscura {
namespace {

TEST(StaleTemporaries, RecognisesTheRunIdInTemporaryNames) {
  EXPECT_EQ(temporary_run_id(".ir.exr.tmp-1234-7"), 1234);
  EXPECT_EQ(temporary_run_id(".o_pk.partial-99"), 99);
  EXPECT_EQ(temporary_run_id(".a.tmp-b.tmp-5-0"), 5);
  for (const char* not_one :
       {"ir.exr", ".ir.exr", "ir.exr.tmp-1-2", ".ir.exr.tmp-", ".x.tmp-12", ".x.tmp-12-",
        ".x.tmp-a-1", ".x.partial-12x", ".x.tmp-0-1", ".tmp-5-1"})
    EXPECT_FALSE(temporary_run_id(not_one)) << not_one;
}

class StaleTemporariesDir : public testing::TempDirTest {};

TEST_F(StaleTemporariesDir, RemovesOnlyThoseOfDeadRuns) {
  // 999999999 is above Linux's largest pid (2^22): no such process.
  std::ofstream(dir_ / ".a.exr.tmp-999999999-0") << "x";
  fs::create_directory(dir_ / ".o.partial-999999999");
  std::ofstream(dir_ / ".o.partial-999999999" / "keyframe_0000.vdb") << "x";
  const std::string mine = ".b.exr.tmp-" + std::to_string(::getpid()) + "-0";
  std::ofstream(dir_ / mine) << "x";
  std::ofstream(dir_ / "a.exr") << "x";
  std::ofstream(dir_ / ".hidden") << "x";
  EXPECT_EQ(remove_stale_temporaries(dir_), 2u);
  EXPECT_FALSE(fs::exists(dir_ / ".a.exr.tmp-999999999-0"));
  EXPECT_FALSE(fs::exists(dir_ / ".o.partial-999999999"));
  EXPECT_TRUE(fs::exists(dir_ / mine));
  EXPECT_TRUE(fs::exists(dir_ / "a.exr"));
  EXPECT_TRUE(fs::exists(dir_ / ".hidden"));
  EXPECT_EQ(remove_stale_temporaries(dir_ / "missing"), 0u);
}

TEST_F(StaleTemporariesDir, AtomicFileTemporariesCarryTheRunId) {
  const AtomicFile f(dir_ / "out.exr");
  EXPECT_EQ(temporary_run_id(f.temp_path().filename().string()), static_cast<long>(::getpid()));
}

}  // namespace
}  // namespace obscura
