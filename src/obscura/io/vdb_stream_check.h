#pragma once
// A walk over a whole OpenVDB file (header, file metadata, grid descriptors
// and every float grid's tree, vdb_grid_check.h) that checks every length,
// offset and compressed chunk before OpenVDB reads it. OpenVDB allocates
// what the file says: a length read past the end of a truncated file (a
// keyframe cut at 100 bytes took 5-13 GB before failing), a compressed
// chunk's size (a mutated one asked for 128 TB), a metadata array's count.
// A grid whose data ends past the end of the file (cut by one byte) is
// refused here too.
#include <filesystem>

namespace obscura::vdb_format {

// Throws InputError naming the file and the part (header, a metadata entry, a
// grid) that does not fit in it.
void check_vdb_stream(const std::filesystem::path& path);

}  // namespace obscura::vdb_format
