#pragma once
// Checks a block of OpenVDB metadata (the file's, or a grid's) before
// OpenVDB reads it (vdb_stream_check.h). Internal to io/.
#include <string>

#include "obscura/io/vdb_stream_reader.h"

namespace obscura::vdb_format {

// Walks an int32 entry count and the entries from the reader's position; on
// return the reader is past the block. `part` names the block ("file
// metadata", "grid density metadata") in messages. Every entry of a type
// OpenVDB knows must have the size OpenVDB will read, or OpenVDB and this
// walk part ways.
void check_metadata_block(VdbStreamReader& r, const std::string& part);

}  // namespace obscura::vdb_format
