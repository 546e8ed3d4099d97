#pragma once
// Checks one compressed chunk of an OpenVDB file by decompressing it into a
// scratch buffer of the size the reader expects. OpenVDB's own readers trust
// a chunk: bloscFromStream decompresses as far as the blosc header says, past
// the chunk it read when the header lies, and a chunk that fails to
// decompress throws from inside RootNode::readTopology after a child node
// was allocated and before it is owned, which leaks it. Internal to io/.
#include <cstddef>
#include <optional>
#include <string>

namespace obscura::vdb_format {

// Empty when `cbytes` bytes at `data` are one blosc buffer that decompresses
// to exactly `expected_bytes`; else what is wrong. `padded`: the chunk was
// written by points/StreamCompression's bloscCompress, which pads a buffer
// shorter than 128 bytes to 128 (OpenVDB's metadata arrays).
std::optional<std::string> blosc_chunk_problem(const unsigned char* data, std::size_t cbytes,
                                               std::size_t expected_bytes, bool padded = false);

// The same for a zlib stream (OpenVDB's COMPRESS_ZIP).
std::optional<std::string> zip_chunk_problem(const unsigned char* data, std::size_t cbytes,
                                             std::size_t expected_bytes);

}  // namespace obscura::vdb_format
