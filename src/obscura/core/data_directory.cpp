#include "obscura/core/data_directory.h"

#include <cstdlib>

#include "obscura/core/version.h"

namespace obscura {

std::filesystem::path data_directory() {
  if (const char* env = std::getenv("OBSCURA_DATA_DIR"); env && *env) return env;
  // The source tree while it exists (a build used in place), else the
  // installed copy.
  std::error_code ec;
  if (std::filesystem::is_directory(kSourceDataDirectory, ec)) return kSourceDataDirectory;
  return kInstalledDataDirectory;
}

}  // namespace obscura
