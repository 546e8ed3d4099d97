#pragma once
// Checks a block of OpenVDB metadata (the file's, or a grid's) before
// OpenVDB reads it (vdb_stream_check.h). Internal to io/.
#include <string>

#include "obscura/io/vdb_stream_reader.h"

namespace obscura::vdb_format {

// What a grid's metadata decides about how OpenVDB reads the grid's data.
struct MetadataFacts {
  // "is_saved_as_half_float": OpenVDB reads a float tree's values as 16-bit
  // halves when this entry says so, whatever the grid descriptor's type
  // says (GridBase::saveFloatAsHalf, after readMeta replaced the metadata
  // the descriptor set). False when the entry is absent.
  bool saved_as_half = false;
};

// Walks an int32 entry count and the entries from the reader's position; on
// return the reader is past the block. `part` names the block ("file
// metadata", "grid density metadata") in messages. Every entry of a type
// OpenVDB knows must have the size OpenVDB will read, or OpenVDB and this
// walk part ways; a bool must be 0 or 1 (OpenVDB loads the byte as a bool),
// and "is_saved_as_half_float" must be a bool.
MetadataFacts check_metadata_block(VdbStreamReader& r, const std::string& part);

}  // namespace obscura::vdb_format
