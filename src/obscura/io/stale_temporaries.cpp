#include "obscura/io/stale_temporaries.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <string>
#include <system_error>

namespace obscura {
namespace {

bool run_alive(long pid) {
  if (pid == static_cast<long>(::getpid())) return true;
  // Signal 0 only checks: EPERM means the process exists under another user.
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

// The digits at the start of `s` as a pid, and where they end.
std::optional<long> leading_pid(std::string_view s, std::size_t& used) {
  long pid = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), pid);
  if (ec != std::errc() || ptr == s.data() || pid <= 0) return std::nullopt;
  used = static_cast<std::size_t>(ptr - s.data());
  return pid;
}

}  // namespace

std::optional<long> temporary_run_id(std::string_view name) {
  if (name.size() < 2 || name[0] != '.') return std::nullopt;
  for (const std::string_view marker : {std::string_view(".tmp-"), std::string_view(".partial-")}) {
    const std::size_t at = name.rfind(marker);
    if (at == std::string_view::npos || at == 0) continue;
    const std::string_view rest = name.substr(at + marker.size());
    std::size_t used = 0;
    const auto pid = leading_pid(rest, used);
    if (!pid) continue;
    const std::string_view tail = rest.substr(used);
    // ".tmp-<pid>-<counter>" or ".partial-<pid>".
    if (marker == ".tmp-") {
      std::size_t counter_used = 0;
      if (tail.size() < 2 || tail[0] != '-') continue;
      long counter = 0;
      const auto [ptr, ec] = std::from_chars(tail.data() + 1, tail.data() + tail.size(), counter);
      counter_used = static_cast<std::size_t>(ptr - tail.data());
      if (ec != std::errc() || counter_used != tail.size()) continue;
    } else if (!tail.empty()) {
      continue;
    }
    return pid;
  }
  return std::nullopt;
}

std::size_t remove_stale_temporaries(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::size_t removed = 0;
  fs::directory_iterator it(dir.empty() ? fs::path(".") : dir, ec);
  if (ec) return 0;
  for (const fs::directory_entry& e : it) {
    const auto pid = temporary_run_id(e.path().filename().string());
    if (!pid || run_alive(*pid)) continue;
    std::error_code rm;
    if (fs::remove_all(e.path(), rm) > 0 && !rm) ++removed;
  }
  return removed;
}

}  // namespace obscura
