#pragma once
// Checks one grid's data in an OpenVDB file before OpenVDB reads it
// (vdb_stream_check.h): its compression flags, metadata and transform, and,
// for float grids (the only ones obscura reads), the whole tree: every node
// mask, every compressed chunk decompressed against the size OpenVDB will
// expect, and the memory the tree will take checked against the limit
// (core/memory_limit.h). The layout is OpenVDB's (file format 222-224):
// io/Archive.cc readGrid, tree/RootNode.h, InternalNode.h and LeafNode.h
// readTopology and readBuffers, io/Compression.h readCompressedValues.
// Internal to io/.
#include <cstdint>
#include <string>

#include "obscura/io/vdb_stream_reader.h"

namespace obscura::vdb_format {

// A grid as its descriptor gives it.
struct GridExtent {
  std::string part;       // "grid density", for messages
  std::string type;       // the descriptor's type, "_HalfFloat" included
  bool instance = false;  // shares another grid's tree and stores none
  std::uint64_t grid_pos = 0;
  std::uint64_t block_pos = 0;  // where the leaf buffers begin
  std::uint64_t end_pos = 0;
};

// Walks the grid from the reader's position (its grid_pos) and leaves it at
// end_pos.
void check_grid_data(VdbStreamReader& r, const GridExtent& grid);

}  // namespace obscura::vdb_format
