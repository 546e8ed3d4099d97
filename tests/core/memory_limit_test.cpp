// The process-wide memory limit (core/memory_limit.h): sizes as people write
// them, who may set the limit, and the refusal's message.
#include "obscura/core/memory_limit.h"

#include <gtest/gtest.h>

#include "support/input_error.h"

namespace obscura {
namespace {

using testing::contains;

class MemoryLimit : public ::testing::Test {
 protected:
  void TearDown() override { reset_memory_limit(); }
};

TEST_F(MemoryLimit, ParsesBinaryAndDecimalSizes) {
  EXPECT_EQ(parse_memory_size("4GiB"), 4ull << 30);
  EXPECT_EQ(parse_memory_size("4G"), 4ull << 30);
  EXPECT_EQ(parse_memory_size("4gib"), 4ull << 30);
  EXPECT_EQ(parse_memory_size("500MB"), 500000000ull);
  EXPECT_EQ(parse_memory_size("1.5MiB"), 1572864ull);
  EXPECT_EQ(parse_memory_size("2048"), 2048ull);
  EXPECT_EQ(parse_memory_size("1TiB"), 1ull << 40);
  for (const char* bad : {"", "GiB", "4 GiB", "-1G", "0", "4XB", "nan", "1e30G", "0.1"})
    EXPECT_FALSE(parse_memory_size(bad)) << bad;
}

TEST_F(MemoryLimit, DefaultIsAFractionOfTheAvailableMemory) {
  const double available = static_cast<double>(available_memory_bytes());
  EXPECT_NEAR(static_cast<double>(memory_limit_bytes()), kDefaultMemoryFraction * available,
              0.25 * available);  // MemAvailable moves while the suite runs
  EXPECT_GT(memory_limit_bytes(), 0u);
}

TEST_F(MemoryLimit, TheCommandLineWinsOverTheScene) {
  set_memory_limit(1000, MemoryLimitSource::kCommandLine);
  set_memory_limit(5000, MemoryLimitSource::kScene);
  EXPECT_EQ(memory_limit_bytes(), 1000u);
  EXPECT_TRUE(contains(memory_limit_text(), "--max-memory")) << memory_limit_text();
  reset_memory_limit();
  set_memory_limit(5000, MemoryLimitSource::kScene);
  EXPECT_EQ(memory_limit_bytes(), 5000u);
  EXPECT_TRUE(contains(memory_limit_text(), "max_memory")) << memory_limit_text();
  set_memory_limit(1000, MemoryLimitSource::kCommandLine);
  EXPECT_EQ(memory_limit_bytes(), 1000u);
}

TEST_F(MemoryLimit, RefusalSaysWhatItNeedsAndTheLimit) {
  set_memory_limit(1ull << 30, MemoryLimitSource::kCommandLine);
  EXPECT_NO_THROW(check_memory(1ull << 30, "f.vdb", "dims", "a grid"));
  const InputError e = testing::expect_input_error(
      [] { check_memory(3ull << 30, "f.vdb", "dims", "grid 10x10x10"); });
  EXPECT_EQ(e.file(), "f.vdb");
  EXPECT_EQ(e.field(), "dims");
  EXPECT_EQ(e.detail(),
            "grid 10x10x10 needs 3 GiB but only 1 GiB of memory is available (the limit set by "
            "--max-memory)");
}

TEST_F(MemoryLimit, CheckedProductDetectsOverflow) {
  EXPECT_EQ(checked_product({16384, 16384, 64 * 16}), 16384ull * 16384 * 1024);
  EXPECT_FALSE(checked_product({1ull << 32, 1ull << 32}));
  EXPECT_EQ(checked_product({}), 1u);
}

}  // namespace
}  // namespace obscura
