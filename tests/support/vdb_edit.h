#pragma once
// Editing keyframe files by hand with OpenVDB directly, bypassing obscura's
// writers (which would refuse most edits), to test how readers treat files
// other tools, or careless hands, produce.
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <string>

namespace obscura::testing {

// Loads every grid and the file metadata of `src`, lets `edit` change them,
// and writes the result to `dst`. Call openvdb::initialize() first.
inline void rewrite_by_hand(
    const std::filesystem::path& src, const std::filesystem::path& dst,
    const std::function<void(openvdb::GridPtrVec&, openvdb::MetaMap&)>& edit) {
  openvdb::io::File in(src.string());
  in.open(false);
  openvdb::GridPtrVecPtr grids = in.getGrids();
  openvdb::MetaMap::Ptr meta = in.getMetadata();
  in.close();
  edit(*grids, *meta);
  openvdb::io::File out(dst.string());
  out.write(*grids, *meta);
  out.close();
}

inline openvdb::FloatGrid::Ptr find_grid(openvdb::GridPtrVec& grids, const std::string& name) {
  for (auto& g : grids)
    if (g->getName() == name) return openvdb::gridPtrCast<openvdb::FloatGrid>(g);
  return nullptr;
}

inline void remove_grid(openvdb::GridPtrVec& grids, const std::string& name) {
  std::erase_if(grids, [&](const openvdb::GridBase::Ptr& g) { return g->getName() == name; });
}

}  // namespace obscura::testing
