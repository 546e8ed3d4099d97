#include "obscura/io/vdb_keyframe_grids.h"

#include <fmt/format.h>

#include <charconv>
#include <stdexcept>
#include <system_error>

#include "obscura/core/error.h"
#include "obscura/io/atomic_file.h"
#include "obscura/io/vdb_keyframe_placement.h"

namespace obscura::vdb_format {
namespace {

// If a grid carries one of our per-grid metadata fields, it must agree with
// the file; grids from other tools may omit them.
void check_grid_metadata(const openvdb::GridBase& g, const GridSpec& spec,
                         const std::string& file) {
  const std::string& name = spec.name;
  if (auto u = g.getMetadata<openvdb::StringMetadata>("units")) {
    if (u->value() != spec.units)
      throw InputError(
          file, name + ".units",
          fmt::format("units '{}' but this grid must be in '{}'", u->value(), spec.units));
  }
  if (!spec.species.empty()) {
    if (auto m = g[std::string("species")]) {
      auto s = dynamic_cast<const openvdb::StringMetadata*>(m.get());
      if (!s)
        throw InputError(file, name + ".species",
                         fmt::format("grid metadata has type {}, expected string", m->typeName()));
      if (s->value() != spec.species)
        throw InputError(
            file, name + ".species",
            fmt::format("species '{}' differs from species_optics, which names it '{}'", s->value(),
                        spec.species));
    }
  }
  const int k = spec.spectral_index;
  if (k < 0) return;
  if (auto m = g[std::string("spectral_index")]) {
    long long idx = -1;
    if (auto i32 = dynamic_cast<const openvdb::Int32Metadata*>(m.get()))
      idx = i32->value();
    else if (auto i64 = dynamic_cast<const openvdb::Int64Metadata*>(m.get()))
      idx = i64->value();
    else
      throw InputError(file, name + ".spectral_index",
                       fmt::format("grid metadata has type {}, expected int", m->typeName()));
    if (idx != k)
      throw InputError(file, name + ".spectral_index",
                       fmt::format("spectral_index {} does not match the grid name", idx));
  }
  if (auto m = g[std::string("wavelength_um")]) {
    auto d = dynamic_cast<const openvdb::DoubleMetadata*>(m.get());
    if (!d)
      throw InputError(file, name + ".wavelength_um",
                       fmt::format("grid metadata has type {}, expected double", m->typeName()));
    if (d->value() != spec.wavelength_um)
      throw InputError(file, name + ".wavelength_um",
                       fmt::format("wavelength {} µm differs from wavelengths_um[{}] = {} µm",
                                   d->value(), k, spec.wavelength_um));
  }
}

}  // namespace

void check_no_extra_indexed_grids(openvdb::io::File& f, std::initializer_list<const char*> prefixes,
                                  int n, const std::string& file,
                                  const std::function<std::string(int)>& problem) {
  for (auto it = f.beginName(); it != f.endName(); ++it) {
    const std::string name = *it;
    for (const char* prefix : prefixes) {
      const std::string p(prefix);
      if (name.size() != p.size() + 3 || name.compare(0, p.size(), p) != 0) continue;
      int idx = 0;
      const auto [end, ec] =
          std::from_chars(name.data() + p.size(), name.data() + name.size(), idx);
      if (ec == std::errc() && end == name.data() + name.size() && idx >= n)
        throw InputError(file, name, problem(idx));
    }
  }
}

GridPlacement read_layout_placement(openvdb::io::File& f, const openvdb::MetaMap& file_metadata,
                                    const std::vector<GridSpec>& layout, const GridDims& dims,
                                    const std::string& file) {
  std::vector<openvdb::GridBase::Ptr> headers;
  const openvdb::GridBase* reference = nullptr;
  for (const GridSpec& spec : layout) {
    if (!f.hasGrid(spec.name)) throw InputError(file, spec.name, "grid is missing");
    openvdb::GridBase::Ptr h;
    try {
      h = f.readGridMetadata(spec.name);
    } catch (const openvdb::Exception& e) {
      throw InputError(file, spec.name, fmt::format("cannot read grid header ({})", e.what()));
    }
    if (!h->isType<openvdb::FloatGrid>())
      throw InputError(file, spec.name,
                       fmt::format("grid has type {}, expected a float grid", h->type()));
    if (spec.name == kTransformGrid) reference = h.get();
    headers.push_back(h);
  }
  if (!reference) throw std::logic_error("vdb_keyframe: a layout without temperature");
  const GridPlacement placement =
      transform_to_placement(reference->constTransform(), file, kTransformGrid);
  for (std::size_t c = 0; c < headers.size(); ++c)
    if (!(headers[c]->constTransform() == reference->constTransform()))
      throw InputError(file, layout[c].name,
                       "grid transform differs from the 'temperature' grid's; all grids of a "
                       "keyframe must share one placement");
  for (std::size_t c = 0; c < headers.size(); ++c)
    check_grid_metadata(*headers[c], layout[c], file);

  // Prefer the exact placement written beside the transform, when it agrees with it.
  if (auto m = file_metadata.getMetadata<openvdb::StringMetadata>("placement")) {
    const auto parsed = parse_placement(m->value());
    if (!parsed)
      throw InputError(file, "placement",
                       fmt::format("'{}' is not a placement record", m->value()));
    if (!placements_agree(*parsed, placement, dims, 1e-6))
      throw InputError(file, "placement",
                       "disagrees with the grids' transform (the file was edited inconsistently)");
    return *parsed;
  }
  return placement;
}

void read_dense_grid(openvdb::io::File& f, const std::string& name, const GridDims& dims,
                     float* out, const std::string& file) {
  openvdb::FloatGrid::Ptr g;
  try {
    g = openvdb::gridPtrCast<openvdb::FloatGrid>(f.readGrid(name));
  } catch (const openvdb::Exception& e) {
    throw InputError(file, name, fmt::format("cannot read grid ({})", e.what()));
  }
  const openvdb::CoordBBox bounds = dense_bbox(dims);
  const openvdb::CoordBBox active = g->evalActiveVoxelBoundingBox();
  if (!active.empty() && !bounds.isInside(active))
    throw InputError(
        file, name,
        fmt::format("active voxels span [{},{},{}]..[{},{},{}], outside the grid "
                    "dims [0,0,0]..[{},{},{}]",
                    active.min().x(), active.min().y(), active.min().z(), active.max().x(),
                    active.max().y(), active.max().z(), dims.nx - 1, dims.ny - 1, dims.nz - 1));
  DenseXYZ dense(bounds, out);
  openvdb::tools::copyToDense(*g, dense);
}

openvdb::FloatGrid::Ptr make_float_grid(const GridSpec& spec, const float* values,
                                        const GridDims& d, const openvdb::math::Transform& xf) {
  auto g = openvdb::FloatGrid::create(/*background=*/0.0f);
  g->setName(spec.name);
  g->setTransform(xf.copy());
  g->setGridClass(spec.fog_volume ? openvdb::GRID_FOG_VOLUME : openvdb::GRID_UNKNOWN);
  g->insertMeta("units", openvdb::StringMetadata(spec.units));
  if (spec.spectral_index >= 0) {
    g->insertMeta("spectral_index", openvdb::Int32Metadata(spec.spectral_index));
    g->insertMeta("wavelength_um", openvdb::DoubleMetadata(spec.wavelength_um));
  }
  if (!spec.species.empty()) g->insertMeta("species", openvdb::StringMetadata(spec.species));
  // Dense only reads through this pointer here (copyFromDense takes it const);
  // the const_cast is for Dense's constructor, which has no const overload.
  const DenseXYZ dense(dense_bbox(d), const_cast<float*>(values));
  // Tolerance 0: only exact zeros become inactive background, so every other
  // value is stored bit for bit.
  openvdb::tools::copyFromDense(dense, *g, 0.0f);
  return g;
}

void write_keyframe_file(const std::filesystem::path& path, const openvdb::GridPtrVec& grids,
                         const openvdb::MetaMap& meta) {
  AtomicFile out(path);
  try {
    openvdb::io::File f(out.temp_path().string());
    f.write(grids, meta);
    f.close();
  } catch (const openvdb::Exception& e) {
    throw Error(fmt::format("cannot write cloud keyframe {}: {}", path.string(), e.what()));
  }
  out.commit();
}

}  // namespace obscura::vdb_format
