#include "obscura/io/vdb_open.h"

#include <fmt/format.h>

#include <system_error>

#include "obscura/core/error.h"
#include "obscura/io/vdb_keyframe_layout.h"
#include "obscura/io/vdb_stream_check.h"

namespace obscura::vdb_format {

std::unique_ptr<openvdb::io::File> open_checked_vdb_file(const std::filesystem::path& path) {
  ensure_openvdb_initialized();
  const std::string file = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(file, "",
                     std::filesystem::exists(path, ec) ? "is not a regular file" : "no such file");

  // Every length and offset against the file's size first: OpenVDB allocates
  // what a truncated file's garbage says (vdb_stream_check.h).
  check_vdb_stream(path);

  auto f = std::make_unique<openvdb::io::File>(file);
  try {
    // No delayed loading: readGrid then reads the voxel data at once, so a
    // truncated file fails there, where the error can name the grid, and not
    // later inside copyToDense's worker threads.
    f->open(/*delayLoad=*/false);
  } catch (const openvdb::Exception& e) {
    throw InputError(file, "", fmt::format("not a readable OpenVDB file ({})", e.what()));
  }
  return f;
}

}  // namespace obscura::vdb_format
