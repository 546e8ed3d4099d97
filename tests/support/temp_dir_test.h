#pragma once
// A GoogleTest fixture that gives each test its own empty scratch folder,
// removed afterwards. The name carries the suite, the test and the process id,
// so tests run in parallel by ctest never share a folder.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace obscura::testing {

class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    // Parameterised tests have "/" in their names: one flat folder each.
    std::string name = std::string("obscura_") + info->test_suite_name() + "_" + info->name() +
                       "_" + std::to_string(::getpid());
    for (char& c : name)
      if (c == '/') c = '_';
    dir_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path dir_;
};

}  // namespace obscura::testing
