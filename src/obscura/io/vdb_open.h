#pragma once
// Opening an OpenVDB file for reading, the one way every reader of VDB files
// does it (cloud keyframes, other tools' density files): the path checked,
// the whole file walked (vdb_stream_check.h) before OpenVDB reads a byte,
// then opened without delayed loading. Internal to io/.
#include <openvdb/io/File.h>

#include <filesystem>
#include <memory>

namespace obscura::vdb_format {

// Throws InputError naming the file: missing, not a regular file, refused by
// the walk, or not readable by OpenVDB.
std::unique_ptr<openvdb::io::File> open_checked_vdb_file(const std::filesystem::path& path);

}  // namespace obscura::vdb_format
