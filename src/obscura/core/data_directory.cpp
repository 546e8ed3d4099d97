#include "obscura/core/data_directory.h"

#include <cstdlib>

#include "obscura/core/version.h"

namespace obscura {

std::filesystem::path data_directory() {
  if (const char* env = std::getenv("OBSCURA_DATA_DIR"); env && *env) return env;
  return kSourceDataDirectory;
}

}  // namespace obscura
