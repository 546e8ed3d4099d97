#include "obscura/io/atomic_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <system_error>

#include "obscura/core/error.h"

namespace obscura {
namespace {

std::atomic<unsigned long long> g_temp_counter{0};

[[noreturn]] void throw_errno(const std::string& what, const std::filesystem::path& path, int err) {
  throw Error(what + " " + path.string() + ": " + std::strerror(err));
}

// fsync so that a power loss after the rename cannot leave an empty final file
// (the rename may reach the disk before the data otherwise).
void fsync_path(const std::filesystem::path& path) {
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw_errno("cannot open", path, errno);
  int rc = ::fsync(fd);
  int err = errno;
  ::close(fd);
  if (rc != 0) throw_errno("cannot fsync", path, err);
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path final_path) : final_path_(std::move(final_path)) {
  if (final_path_.filename().empty()) {
    throw Error("cannot write output: path has no file name: " + final_path_.string());
  }
  std::filesystem::path dir = final_path_.parent_path();
  if (!dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw Error("cannot create directory " + dir.string() + ": " + ec.message());
  }
  // fmt rather than operator+ chains: GCC 12 emits a false -Wrestrict for
  // those at -O2 (GCC bug 105329).
  temp_path_ = dir / fmt::format(".{}.tmp-{}-{}", final_path_.filename().string(),
                                 static_cast<long>(::getpid()), g_temp_counter++);
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  std::error_code ec;  // destructors must not throw; a leftover temp is harmless
  std::filesystem::remove(temp_path_, ec);
}

void AtomicFile::commit() {
  if (committed_) throw Error("AtomicFile::commit called twice for " + final_path_.string());
  fsync_path(temp_path_);
  if (std::rename(temp_path_.c_str(), final_path_.c_str()) != 0) {
    int err = errno;
    throw Error("cannot rename " + temp_path_.string() + " to " + final_path_.string() + ": " +
                std::strerror(err));
  }
  committed_ = true;
}

void write_text_file_atomic(const std::filesystem::path& path, std::string_view content) {
  AtomicFile file(path);
  std::FILE* f = std::fopen(file.temp_path().c_str(), "wb");
  if (f == nullptr) throw_errno("cannot open", file.temp_path(), errno);
  size_t written = std::fwrite(content.data(), 1, content.size(), f);
  int write_err = errno;
  bool ok = written == content.size();
  int close_rc = std::fclose(f);
  int close_err = errno;
  if (!ok) throw_errno("cannot write", file.temp_path(), write_err);
  if (close_rc != 0) throw_errno("cannot write", file.temp_path(), close_err);
  file.commit();
}

}  // namespace obscura
