#pragma once
// Outputs are never half-written: a writer fills a temporary file in the same
// directory as the final path and renames it over the final path only when the
// whole file is written. rename(2) within one file system is atomic, so a
// reader (or a crashed run) sees either the old file or the complete new one.
#include <filesystem>
#include <string_view>

namespace obscura {

class AtomicFile {
 public:
  // Creates the parent directory of `final_path` if missing. Nothing is
  // written until the caller writes temp_path(). Throws obscura::Error.
  explicit AtomicFile(std::filesystem::path final_path);
  // Removes the temporary file unless commit() succeeded.
  ~AtomicFile();

  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::filesystem::path& final_path() const { return final_path_; }
  // A unique name in the final directory (".<name>.tmp-<pid>-<counter>"), so
  // the rename never crosses a file system and concurrent writers never collide.
  const std::filesystem::path& temp_path() const { return temp_path_; }

  // Flushes the temporary file to disk and renames it over the final path.
  // Throws obscura::Error (naming the path and the system error) on failure.
  void commit();
  bool committed() const { return committed_; }

 private:
  std::filesystem::path final_path_;
  std::filesystem::path temp_path_;
  bool committed_ = false;
};

// Writes `content` (bytes, verbatim) to `path` through an AtomicFile.
void write_text_file_atomic(const std::filesystem::path& path, std::string_view content);

}  // namespace obscura
