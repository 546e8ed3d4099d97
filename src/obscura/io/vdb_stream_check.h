#pragma once
// A walk over an OpenVDB file's header, file metadata and grid descriptors
// that checks every length and offset against the file's size before
// OpenVDB reads it. OpenVDB reads a length past the end of a truncated file
// into an uninitialised integer and allocates whatever it holds (a keyframe
// cut at 100 bytes took 5-13 GB before failing); a grid whose data ends past
// the end of the file (cut by one byte) is refused here too.
#include <filesystem>

namespace obscura::vdb_format {

// Throws InputError naming the file and the part (header, a metadata entry, a
// grid) that does not fit in it.
void check_vdb_stream(const std::filesystem::path& path);

}  // namespace obscura::vdb_format
