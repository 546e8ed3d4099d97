#include "obscura/io/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "obscura/core/error.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

namespace fs = std::filesystem;

class AtomicFileTest : public testing::TempDirTest {
 protected:
  static std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  static void write(const fs::path& p, const std::string& s) {
    std::ofstream out(p, std::ios::binary);
    out << s;
  }
};

TEST_F(AtomicFileTest, FinalFileAppearsOnlyOnCommit) {
  const fs::path final_path = dir_ / "sub" / "out.txt";
  AtomicFile file(final_path);
  EXPECT_TRUE(fs::is_directory(final_path.parent_path()));  // parent created
  EXPECT_EQ(file.temp_path().parent_path(), final_path.parent_path());
  EXPECT_NE(file.temp_path(), final_path);
  write(file.temp_path(), "hello");
  EXPECT_FALSE(fs::exists(final_path));
  file.commit();
  EXPECT_TRUE(file.committed());
  EXPECT_FALSE(fs::exists(file.temp_path()));
  EXPECT_EQ(read(final_path), "hello");
}

TEST_F(AtomicFileTest, TempRemovedWithoutCommit) {
  const fs::path final_path = dir_ / "out.txt";
  fs::path temp;
  {
    AtomicFile file(final_path);
    temp = file.temp_path();
    write(temp, "partial");
    ASSERT_TRUE(fs::exists(temp));
  }
  EXPECT_FALSE(fs::exists(temp));
  EXPECT_FALSE(fs::exists(final_path));
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(AtomicFileTest, AbandonedWriteKeepsOldContent) {
  const fs::path final_path = dir_ / "out.txt";
  write_text_file_atomic(final_path, "old");
  {
    AtomicFile file(final_path);
    write(file.temp_path(), "new but unfinished");
  }
  EXPECT_EQ(read(final_path), "old");
}

TEST_F(AtomicFileTest, TempNamesAreUnique) {
  AtomicFile a(dir_ / "x.bin");
  AtomicFile b(dir_ / "x.bin");
  EXPECT_NE(a.temp_path(), b.temp_path());
}

TEST_F(AtomicFileTest, CommitWithoutTempFileThrows) {
  AtomicFile file(dir_ / "never_written.txt");
  EXPECT_THROW(file.commit(), Error);
  EXPECT_FALSE(fs::exists(dir_ / "never_written.txt"));
}

TEST_F(AtomicFileTest, WriteTextFileAtomicReplacesContent) {
  const fs::path p = dir_ / "a" / "b.json";
  write_text_file_atomic(p, "first");
  write_text_file_atomic(p, std::string("sec\0ond", 7));
  EXPECT_EQ(read(p), std::string("sec\0ond", 7));
  // Only the final file is left: no temporaries.
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(p.parent_path())) ++entries;
  EXPECT_EQ(entries, 1);
}

TEST_F(AtomicFileTest, UnwritableDirectoryThrows) {
  fs::create_directories(dir_);
  write(dir_ / "file", "x");
  // A regular file where a directory is needed cannot be created over.
  EXPECT_THROW(write_text_file_atomic(dir_ / "file" / "out.txt", "y"), Error);
}

}  // namespace
}  // namespace obscura
