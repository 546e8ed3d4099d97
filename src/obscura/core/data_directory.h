#pragma once
// Where obscura's data files live (validation tables, materials): the
// OBSCURA_DATA_DIR environment variable when set, else the data/ folder of the
// source tree this build came from while it exists, else the installed copy
// (<prefix>/share/obscura).
#include <filesystem>

namespace obscura {

std::filesystem::path data_directory();

}  // namespace obscura
