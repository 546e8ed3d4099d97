#include "obscura/io/input_file.h"

#include <fmt/format.h>

#include <system_error>

#include "obscura/core/error.h"

namespace obscura {

void require_regular_file(const std::filesystem::path& path, std::string_view what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  const std::string file = path.string();
  if (st.type() == fs::file_type::not_found)
    throw InputError(file, "", fmt::format("no such file (expected a {})", what));
  if (ec) throw InputError(file, "", fmt::format("cannot open the {}: {}", what, ec.message()));
  if (st.type() == fs::file_type::directory)
    throw InputError(file, "", fmt::format("is a folder, expected a {} file", what));
  if (st.type() != fs::file_type::regular)
    throw InputError(file, "", fmt::format("is not a regular file (expected a {})", what));
}

}  // namespace obscura
