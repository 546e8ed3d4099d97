#pragma once
// The first check of every input file, before it is opened: a folder or a
// missing path is named as such (reading a folder as a file succeeds on Linux
// and then fails with a misleading parse error).
#include <filesystem>
#include <string_view>

namespace obscura {

// Throws InputError naming `path` unless it is a regular file (or a link to one).
// `what` says what was expected ("scene JSON", "OBJ mesh").
void require_regular_file(const std::filesystem::path& path, std::string_view what);

}  // namespace obscura
