#include "obscura/core/check.h"

#include <string_view>

namespace obscura {

void fail_check(const char* file, int line, const char* condition, const std::string& detail) {
  // The path below src/ is enough to find the line.
  std::string_view path(file);
  if (const auto at = path.rfind("src/obscura/"); at != std::string_view::npos)
    path.remove_prefix(at + 4);
  std::string message = "internal error: " + std::string(path) + ":" + std::to_string(line) +
                        ": check failed: " + condition;
  if (!detail.empty()) message += " (" + detail + ")";
  throw InternalError(message);
}

}  // namespace obscura
