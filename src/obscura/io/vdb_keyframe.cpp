#include "obscura/io/vdb_keyframe.h"

#include <fmt/format.h>
#include <openvdb/io/File.h>
#include <openvdb/math/Transform.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <stdexcept>
#include <system_error>

#include "obscura/core/error.h"
#include "obscura/io/atomic_file.h"
#include "obscura/io/json_reader.h"

namespace obscura {
namespace {

using DenseXYZ = openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ>;

constexpr const char* kFormatName = "cloud-keyframe";
constexpr const char* kFormSpectral = "spectral";
constexpr const char* kFormSpecies = "species";
constexpr const char* kCoefficientUnits = "1/m";
constexpr const char* kConcentrationUnits = "g/m3";
constexpr const char* kTemperatureUnits = "K";
constexpr const char* kTransformGrid = "temperature";

// Relative tolerance for "uniform" scale and "orthonormal" rotation in a
// transform read from a file: tools that store the map in single precision
// (or compose it from Euler angles) leave errors of ~1e-7, which are harmless.
constexpr double kTransformTolerance = 1e-6;

// File-level metadata keys this format owns (either form); extra_metadata
// must not use them.
const std::set<std::string>& reserved_keys() {
  static const std::set<std::string> keys = {"obscura_format",
                                             "obscura_format_version",
                                             "obscura_form",
                                             "time_s",
                                             "wavelengths_um",
                                             "spectral_count",
                                             "dims",
                                             "coefficient_units",
                                             "temperature_units",
                                             "placement",
                                             "species_count",
                                             "species_optics",
                                             "concentration_units"};
  return keys;
}

// openvdb::initialize registers grid, map and metadata types; reading a file
// before it fails with "unregistered type" errors, and it is not thread-safe.
void ensure_openvdb_initialized() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

// One float grid of a keyframe file, as written and as expected on reading
// (docs/formats.md): its name, units and class, and the per-grid metadata
// that ties it to the file.
struct GridSpec {
  std::string name;
  std::string units;
  bool fog_volume = false;  // grid class: fog volume (densities) or unknown
  int spectral_index = -1;  // spectral grids: k, with wavelength_um
  double wavelength_um = 0.0;
  std::string species;  // concentration grids: the species' name
};

// The grids of the spectral form, in VoxelGrid channel order (σa, σs, g per
// wavelength, then temperature); names as VoxelGrid::channel_name.
std::vector<GridSpec> spectral_layout(const std::vector<double>& wavelengths_um) {
  const int n = static_cast<int>(wavelengths_um.size());
  std::vector<GridSpec> layout;
  for (const auto& [prefix, units, fog] :
       {std::tuple{"sigma_a_", kCoefficientUnits, true},
        std::tuple{"sigma_s_", kCoefficientUnits, true}, std::tuple{"g_", "1", false}})
    for (int k = 0; k < n; ++k)
      layout.push_back({fmt::format("{}{:03d}", prefix, k), units, fog, k, wavelengths_um[k], ""});
  layout.push_back({kTransformGrid, kTemperatureUnits, false, -1, 0.0, ""});
  return layout;
}

// The grids of the species form: one concentration per species, then temperature.
std::vector<GridSpec> species_layout(const std::vector<SpeciesOptics>& species) {
  std::vector<GridSpec> layout;
  for (std::size_t s = 0; s < species.size(); ++s)
    layout.push_back({species_concentration_name(static_cast<int>(s)), kConcentrationUnits, true,
                      -1, 0.0, species[s].name});
  layout.push_back({kTransformGrid, kTemperatureUnits, false, -1, 0.0, ""});
  return layout;
}

openvdb::CoordBBox dense_bbox(const GridDims& d) {
  return openvdb::CoordBBox(openvdb::Coord(0, 0, 0), openvdb::Coord(d.nx - 1, d.ny - 1, d.nz - 1));
}

// The exact affine index→world map of GridPlacement,
//   world = origin + R·(s·(index + ½)),
// in OpenVDB's row-vector convention (world = index·M, translation in row 3).
openvdb::math::Transform::Ptr placement_to_transform(const GridPlacement& p) {
  const double s = p.voxel_size_m;
  const Vec3 t = p.origin_m + p.rotation * Vec3(0.5 * s, 0.5 * s, 0.5 * s);
  if (p.rotation == Mat3::identity()) {
    // Built from the scale itself, so the file stores the exact voxel size:
    // createLinearTransform(Mat4d) simplifies a diagonal matrix into a scale
    // map through a decomposition that changes its last bits (0.1 becomes
    // 0.10000000000000009). OpenVDB's own reader (and Transform::copy) run the
    // same simplification, so obscura reads it back to within a few ulp only.
    auto xf = openvdb::math::Transform::createLinearTransform(s);
    xf->postTranslate(openvdb::Vec3d(t.x, t.y, t.z));
    return xf;
  }
  openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = s * p.rotation.m[c][r];
  m(3, 0) = t.x;
  m(3, 1) = t.y;
  m(3, 2) = t.z;
  return openvdb::math::Transform::createLinearTransform(m);
}

// Inverse of placement_to_transform. The transform holds s·R, not s and R
// apart, and OpenVDB re-simplifies maps as it reads them, so the placement is
// recovered to within a few ulp (~1e-15 relative), not bit for bit.
GridPlacement transform_to_placement(const openvdb::math::Transform& xf, const std::string& file,
                                     const std::string& grid_name) {
  if (!xf.isLinear())
    throw InputError(file, grid_name,
                     fmt::format("transform is a non-linear '{}' map; a cloud keyframe needs a "
                                 "uniform scale, rotation and translation",
                                 xf.mapType()));
  const openvdb::math::Mat4d m = xf.baseMap()->getAffineMap()->getMat4();
  double norm[3];
  for (int r = 0; r < 3; ++r)
    norm[r] = std::sqrt(m(r, 0) * m(r, 0) + m(r, 1) * m(r, 1) + m(r, 2) * m(r, 2));
  // When the three row norms agree exactly (always so for an axis-aligned grid,
  // as sqrt(s·s) == s), take that value so the voxel size round-trips exactly.
  const double s =
      norm[0] == norm[1] && norm[1] == norm[2] ? norm[0] : (norm[0] + norm[1] + norm[2]) / 3.0;
  if (!(std::isfinite(s) && s > 0.0))
    throw InputError(file, grid_name, fmt::format("transform has voxel size {} m", s));
  for (int r = 0; r < 3; ++r)
    if (std::abs(norm[r] - s) > kTransformTolerance * s)
      throw InputError(file, grid_name,
                       fmt::format("transform has non-uniform voxel size ({}, {}, {}) m; cloud "
                                   "keyframes need cubic voxels",
                                   norm[0], norm[1], norm[2]));
  GridPlacement p;
  p.voxel_size_m = s;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) p.rotation.m[c][r] = m(r, c) / s;
  // Columns of R must be orthonormal: anything else is a shear.
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      double d = 0.0;
      for (int k = 0; k < 3; ++k) d += p.rotation.m[k][a] * p.rotation.m[k][b];
      if (std::abs(d - (a == b ? 1.0 : 0.0)) > kTransformTolerance)
        throw InputError(file, grid_name,
                         "transform is sheared (its axes are not perpendicular); cloud keyframes "
                         "need a uniform scale, rotation and translation");
    }
  const Mat3& R = p.rotation;
  const double det = R.m[0][0] * (R.m[1][1] * R.m[2][2] - R.m[1][2] * R.m[2][1]) -
                     R.m[0][1] * (R.m[1][0] * R.m[2][2] - R.m[1][2] * R.m[2][0]) +
                     R.m[0][2] * (R.m[1][0] * R.m[2][1] - R.m[1][1] * R.m[2][0]);
  if (det < 0.0)
    throw InputError(file, grid_name,
                     "transform mirrors the grid (negative determinant); cloud keyframes need a "
                     "proper rotation");
  const Vec3 t(m(3, 0), m(3, 1), m(3, 2));
  p.origin_m = t - p.rotation * Vec3(0.5 * s, 0.5 * s, 0.5 * s);
  if (!is_finite(p.origin_m))
    throw InputError(file, grid_name, "transform translation is not finite");
  return p;
}

std::string format_wavelengths(const std::vector<double>& w) {
  std::string out;
  for (std::size_t k = 0; k < w.size(); ++k) {
    if (k > 0) out += ',';
    out += fmt::format("{:.17g}", w[k]);  // 17 significant digits round-trip any double
  }
  return out;
}

// The placement as exact decimal text ("origin_m=x,y,z;voxel_size_m=s;rotation=r00,...,r22",
// 17 significant digits): OpenVDB re-simplifies transforms on read, which moves
// their last bits, so the exact values travel beside the transform.
std::string format_placement(const GridPlacement& p) {
  std::string out =
      fmt::format("origin_m={:.17g},{:.17g},{:.17g};voxel_size_m={:.17g};rotation=", p.origin_m.x,
                  p.origin_m.y, p.origin_m.z, p.voxel_size_m);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      out += fmt::format("{}{:.17g}", r + c == 0 ? "" : ",", p.rotation.m[r][c]);
  return out;
}

// Parses format_placement's text; nullopt if it is malformed.
std::optional<GridPlacement> parse_placement(const std::string& text) {
  std::vector<double> v;
  std::size_t pos = 0;
  for (const char* key : {"origin_m=", ";voxel_size_m=", ";rotation="}) {
    const std::string k(key);
    if (text.compare(pos, k.size(), k) != 0) return std::nullopt;
    pos += k.size();
    const int count = k == ";voxel_size_m=" ? 1 : (k == "origin_m=" ? 3 : 9);
    for (int i = 0; i < count; ++i) {
      if (i > 0) {
        if (pos >= text.size() || text[pos] != ',') return std::nullopt;
        ++pos;
      }
      double x = 0;
      const auto [end, ec] = std::from_chars(text.data() + pos, text.data() + text.size(), x);
      if (ec != std::errc()) return std::nullopt;
      pos = static_cast<std::size_t>(end - text.data());
      v.push_back(x);
    }
  }
  if (pos != text.size()) return std::nullopt;
  GridPlacement p;
  p.origin_m = {v[0], v[1], v[2]};
  p.voxel_size_m = v[3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) p.rotation.m[r][c] = v[4 + 3 * r + c];
  return p;
}

// True when two placements map every voxel of the grid to the same world
// point within `tolerance` voxels.
bool placements_agree(const GridPlacement& a, const GridPlacement& b, const GridDims& d,
                      double tolerance) {
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 idx((corner & 1) ? d.nx : -1, (corner & 2) ? d.ny : -1, (corner & 4) ? d.nz : -1);
    if (length(a.index_to_world(idx) - b.index_to_world(idx)) > tolerance * a.voxel_size_m)
      return false;
  }
  return true;
}

std::vector<double> parse_wavelengths(const std::string& text, const std::string& file) {
  std::vector<double> out;
  std::size_t pos = 0;
  while (true) {
    const std::size_t comma = std::min(text.find(',', pos), text.size());
    std::size_t b = pos, e = comma;
    while (b < e && text[b] == ' ') ++b;
    while (e > b && text[e - 1] == ' ') --e;
    double v = 0.0;
    const auto [end, ec] = std::from_chars(text.data() + b, text.data() + e, v);
    if (b == e || ec != std::errc() || end != text.data() + e)
      throw InputError(file, "wavelengths_um",
                       fmt::format("'{}' is not a comma-separated list of numbers (entry {} is "
                                   "'{}')",
                                   text, out.size(), text.substr(b, e - b)));
    out.push_back(v);
    if (comma == text.size()) break;
    pos = comma + 1;
  }
  return out;
}

// Typed access to file metadata with errors that name the field.
class MetaReader {
 public:
  MetaReader(const openvdb::MetaMap& meta, std::string file)
      : meta_(meta), file_(std::move(file)) {}

  std::string get_string(const std::string& key) const {
    const auto m = require(key);
    if (auto s = dynamic_cast<const openvdb::StringMetadata*>(m.get())) return s->value();
    throw wrong_type(key, m, "string");
  }
  // Accepts 32- and 64-bit integers: pyopenvdb writes Python ints as int64.
  long long get_int(const std::string& key) const {
    const auto m = require(key);
    if (auto i = dynamic_cast<const openvdb::Int32Metadata*>(m.get())) return i->value();
    if (auto i = dynamic_cast<const openvdb::Int64Metadata*>(m.get())) return i->value();
    throw wrong_type(key, m, "int");
  }
  double get_double(const std::string& key) const {
    const auto m = require(key);
    if (auto d = dynamic_cast<const openvdb::DoubleMetadata*>(m.get())) return d->value();
    if (auto f = dynamic_cast<const openvdb::FloatMetadata*>(m.get())) return f->value();
    throw wrong_type(key, m, "double");
  }
  openvdb::Vec3i get_vec3i(const std::string& key) const {
    const auto m = require(key);
    if (auto v = dynamic_cast<const openvdb::Vec3IMetadata*>(m.get())) return v->value();
    throw wrong_type(key, m, "vec3i");
  }

 private:
  openvdb::Metadata::ConstPtr require(const std::string& key) const {
    auto m = meta_[key];
    if (!m) throw InputError(file_, key, "required file metadata is missing");
    return m;
  }
  InputError wrong_type(const std::string& key, const openvdb::Metadata::ConstPtr& m,
                        const char* expected) const {
    return InputError(
        file_, key, fmt::format("file metadata has type {}, expected {}", m->typeName(), expected));
  }
  const openvdb::MetaMap& meta_;
  std::string file_;
};

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
    if (auto i = dynamic_cast<const openvdb::Int32Metadata*>(m.get()))
      idx = i->value();
    else if (auto i = dynamic_cast<const openvdb::Int64Metadata*>(m.get()))
      idx = i->value();
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

// Refuses a grid named <prefix>NNN (one of `prefixes`) with NNN >= n, e.g.
// sigma_a_005 with spectral_count 5; `problem(NNN)` says why it makes the file
// inconsistent.
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

// The metadata both forms share, read and checked.
struct CommonHeader {
  std::string form;
  double time_s = 0.0;
  std::vector<double> wavelengths_um;
  GridDims dims;
};

CommonHeader read_common_header(const MetaReader& meta, const openvdb::MetaMap& map,
                                const std::string& file) {
  CommonHeader h;
  const std::string format = meta.get_string("obscura_format");
  if (format != kFormatName)
    throw InputError(file, "obscura_format",
                     fmt::format("is '{}', expected '{}'", format, kFormatName));
  const long long version = meta.get_int("obscura_format_version");
  if (version > kCloudKeyframeFormatVersion)
    throw InputError(file, "obscura_format_version",
                     fmt::format("version {} is newer than this obscura reads ({})", version,
                                 kCloudKeyframeFormatVersion));
  if (version < 1)
    throw InputError(file, "obscura_format_version", fmt::format("invalid version {}", version));
  // Files without obscura_form (other tools, older obscura) are spectral.
  h.form = map[std::string("obscura_form")] ? meta.get_string("obscura_form") : kFormSpectral;
  if (h.form != kFormSpectral && h.form != kFormSpecies)
    throw InputError(
        file, "obscura_form",
        fmt::format("is '{}', expected '{}' or '{}'", h.form, kFormSpectral, kFormSpecies));
  if (meta.get_string("temperature_units") != kTemperatureUnits)
    throw InputError(file, "temperature_units",
                     fmt::format("is '{}', expected '{}'", meta.get_string("temperature_units"),
                                 kTemperatureUnits));

  h.time_s = meta.get_double("time_s");
  if (!(std::isfinite(h.time_s) && h.time_s >= 0.0))
    throw InputError(
        file, "time_s",
        fmt::format("time {} s must be finite and >= 0 (seconds after activation)", h.time_s));

  const long long spectral_count = meta.get_int("spectral_count");
  if (spectral_count <= 0 || spectral_count > 999)  // grid names carry 3 digits
    throw InputError(file, "spectral_count",
                     fmt::format("{} must be between 1 and 999", spectral_count));
  h.wavelengths_um = parse_wavelengths(meta.get_string("wavelengths_um"), file);
  if (static_cast<long long>(h.wavelengths_um.size()) != spectral_count)
    throw InputError(file, "wavelengths_um",
                     fmt::format("lists {} wavelengths but spectral_count is {}",
                                 h.wavelengths_um.size(), spectral_count));

  const openvdb::Vec3i d = meta.get_vec3i("dims");
  h.dims = GridDims{d.x(), d.y(), d.z()};
  return h;
}

void require_units(const MetaReader& meta, const std::string& key, const char* want,
                   const std::string& file) {
  const std::string units = meta.get_string(key);
  if (units != want)
    throw InputError(file, key, fmt::format("is '{}', expected '{}'", units, want));
}

// Checks the headers of `layout`'s grids (present, float grids, per-grid
// metadata, one shared transform) without reading voxel data, and returns the
// placement: the exact "placement" record when present and agreeing with the
// transform, else the transform's.
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

// Reads grid `name` into `out` (dims.count() floats, x fastest): voxels not
// stored take the background. Active voxels outside the dims are an error.
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

std::shared_ptr<VoxelGrid> read_spectral_grids(openvdb::io::File& f, const MetaReader& meta,
                                               const openvdb::MetaMap& file_metadata,
                                               CommonHeader& h, const std::string& file) {
  require_units(meta, "coefficient_units", kCoefficientUnits, file);
  const int n = static_cast<int>(h.wavelengths_um.size());
  // Before reading any voxel data: refuse dims that overflow or exceed memory.
  VoxelGrid::checked_storage_bytes(h.dims, n, file);
  check_no_extra_indexed_grids(f, {"sigma_a_", "sigma_s_", "g_"}, n, file, [&](int idx) {
    return fmt::format("grid index {} is beyond spectral_count {}", idx, n);
  });
  const std::vector<GridSpec> layout = spectral_layout(h.wavelengths_um);
  const GridPlacement placement = read_layout_placement(f, file_metadata, layout, h.dims, file);
  auto grid = std::make_shared<VoxelGrid>(h.dims, placement, std::move(h.wavelengths_um), file);
  for (int c = 0; c < grid->channel_count(); ++c) {
    if (layout[c].name != grid->channel_name(c))  // the layout must mirror channel_name
      throw std::logic_error("vdb_keyframe: channel name mismatch for " + layout[c].name);
    read_dense_grid(f, layout[c].name, h.dims, grid->channel(c), file);
  }
  grid->validate(file);
  return grid;
}

// The "species_optics" metadata: a JSON array of {name, wavelengths_um,
// mass_absorption_m2_g, mass_scattering_m2_g, asymmetry}, one per species,
// each at exactly the file's wavelengths.
std::vector<SpeciesOptics> parse_species_optics(const std::string& text, std::size_t count,
                                                const std::vector<double>& wavelengths_um,
                                                const std::string& file) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(file, "species_optics", fmt::format("is not valid JSON ({})", e.what()));
  }
  if (!doc.is_array())
    throw InputError(file, "species_optics", "must be a JSON array with one object per species");
  if (doc.size() != count)
    throw InputError(file, "species_optics",
                     fmt::format("lists {} species but species_count is {}", doc.size(), count));
  std::vector<SpeciesOptics> species;
  for (std::size_t s = 0; s < count; ++s) {
    const std::string field = fmt::format("species_optics/{}", s);
    JsonObject o(doc[s], file, field);
    SpeciesOptics optics;
    optics.name = o.string("name");
    optics.wavelengths_um = o.numbers("wavelengths_um");
    optics.mass_absorption_m2_g = o.numbers("mass_absorption_m2_g");
    optics.mass_scattering_m2_g = o.numbers("mass_scattering_m2_g");
    optics.asymmetry = o.numbers("asymmetry");
    o.finish();
    check_species_optics(optics, wavelengths_um, file, field);
    species.push_back(std::move(optics));
  }
  return species;
}

std::string format_species_optics(const std::vector<SpeciesOptics>& species) {
  nlohmann::json doc = nlohmann::json::array();
  // nlohmann writes the shortest decimal that reads back to the same double.
  for (const SpeciesOptics& o : species)
    doc.push_back({{"name", o.name},
                   {"wavelengths_um", o.wavelengths_um},
                   {"mass_absorption_m2_g", o.mass_absorption_m2_g},
                   {"mass_scattering_m2_g", o.mass_scattering_m2_g},
                   {"asymmetry", o.asymmetry}});
  return doc.dump();
}

SpeciesCloud read_species_grids(openvdb::io::File& f, const MetaReader& meta,
                                const openvdb::MetaMap& file_metadata, CommonHeader& h,
                                const std::string& file) {
  require_units(meta, "concentration_units", kConcentrationUnits, file);
  const long long species_count = meta.get_int("species_count");
  if (species_count <= 0 || species_count > 999)  // grid names carry 3 digits
    throw InputError(file, "species_count",
                     fmt::format("{} must be between 1 and 999", species_count));
  const std::size_t ns = static_cast<std::size_t>(species_count);
  SpeciesCloud cloud;
  cloud.species =
      parse_species_optics(meta.get_string("species_optics"), ns, h.wavelengths_um, file);

  // Before reading any voxel data: the expanded grid and, while it is being
  // expanded, the compact arrays must fit in memory.
  const std::uint64_t expanded =
      VoxelGrid::checked_storage_bytes(h.dims, static_cast<int>(h.wavelengths_um.size()), file);
  std::uint64_t compact = 0;
  if (__builtin_mul_overflow(static_cast<std::uint64_t>(h.dims.count()),
                             static_cast<std::uint64_t>((ns + 1) * sizeof(float)), &compact) ||
      expanded + compact < expanded || expanded + compact > available_memory_bytes())
    throw InputError(
        file, "dims",
        fmt::format("grid {}x{}x{} with {} species and {} wavelengths needs {:.3g} "
                    "GiB but only {:.3g} GiB of memory is available",
                    h.dims.nx, h.dims.ny, h.dims.nz, ns, h.wavelengths_um.size(),
                    (static_cast<double>(expanded) + static_cast<double>(compact)) / 1073741824.0,
                    available_memory_bytes() / 1073741824.0));

  check_no_extra_indexed_grids(f, {"concentration_"}, static_cast<int>(ns), file, [&](int idx) {
    return fmt::format("grid index {} is beyond species_count {}", idx, ns);
  });
  check_no_extra_indexed_grids(f, {"sigma_a_", "sigma_s_", "g_"}, 0, file, [](int) {
    return std::string("spectral grid in a species-form keyframe (obscura_form 'species')");
  });
  const std::vector<GridSpec> layout = species_layout(cloud.species);
  cloud.placement = read_layout_placement(f, file_metadata, layout, h.dims, file);
  cloud.dims = h.dims;
  cloud.wavelengths_um = std::move(h.wavelengths_um);
  const std::size_t count = h.dims.count();
  cloud.concentration_g_m3.resize(ns);
  for (std::size_t s = 0; s < ns; ++s) {
    cloud.concentration_g_m3[s].resize(count);
    read_dense_grid(f, layout[s].name, cloud.dims, cloud.concentration_g_m3[s].data(), file);
  }
  cloud.temperature_k.resize(count);
  read_dense_grid(f, kTransformGrid, cloud.dims, cloud.temperature_k.data(), file);
  validate_species_cloud(cloud, file);
  return cloud;
}

struct ReadResult {
  CloudKeyframe keyframe;
  openvdb::MetaMap::Ptr file_metadata;
  std::string form;
  std::optional<SpeciesCloud> species;  // species form, when asked to keep it
};

ReadResult read_keyframe(const std::filesystem::path& path, bool keep_species) {
  ensure_openvdb_initialized();
  const std::string file = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(file, "",
                     std::filesystem::exists(path, ec) ? "is not a regular file" : "no such file");

  openvdb::io::File f(file);
  try {
    // No delayed loading: readGrid then reads the voxel data at once, so a
    // truncated file fails there, where the error can name the grid, and not
    // later inside copyToDense's worker threads.
    f.open(/*delayLoad=*/false);
  } catch (const openvdb::Exception& e) {
    throw InputError(file, "", fmt::format("not a readable OpenVDB file ({})", e.what()));
  }

  ReadResult result;
  result.file_metadata = f.getMetadata();
  const MetaReader meta(*result.file_metadata, file);
  CommonHeader h = read_common_header(meta, *result.file_metadata, file);
  result.form = h.form;
  result.keyframe.time_s = h.time_s;
  if (h.form == kFormSpecies) {
    SpeciesCloud cloud = read_species_grids(f, meta, *result.file_metadata, h, file);
    f.close();
    result.keyframe.grid = std::make_shared<VoxelGrid>(expand_species(cloud, file));
    if (keep_species) result.species = std::move(cloud);
  } else {
    result.keyframe.grid = read_spectral_grids(f, meta, *result.file_metadata, h, file);
    f.close();
  }
  return result;
}

// --- writing

void check_time_and_metadata(const std::string& file, double time_s,
                             const std::map<std::string, std::string>& extra_metadata) {
  if (!(std::isfinite(time_s) && time_s >= 0.0))
    throw InputError(
        file, "time_s",
        fmt::format("time {} s must be finite and >= 0 (seconds after activation)", time_s));
  for (const auto& [key, value] : extra_metadata) {
    if (key.empty()) throw InputError(file, "metadata", "metadata names must not be empty");
    if (reserved_keys().count(key))
      throw InputError(file, key, "is a reserved cloud-keyframe metadata name");
  }
}

// The file metadata both forms carry.
openvdb::MetaMap common_metadata(const char* form, double time_s,
                                 const std::vector<double>& wavelengths_um, const GridDims& d,
                                 const GridPlacement& placement,
                                 const std::map<std::string, std::string>& extra_metadata) {
  openvdb::MetaMap meta;
  meta.insertMeta("obscura_format", openvdb::StringMetadata(kFormatName));
  meta.insertMeta("obscura_format_version", openvdb::Int32Metadata(kCloudKeyframeFormatVersion));
  meta.insertMeta("obscura_form", openvdb::StringMetadata(form));
  meta.insertMeta("time_s", openvdb::DoubleMetadata(time_s));
  meta.insertMeta("wavelengths_um", openvdb::StringMetadata(format_wavelengths(wavelengths_um)));
  meta.insertMeta("spectral_count",
                  openvdb::Int32Metadata(static_cast<int>(wavelengths_um.size())));
  meta.insertMeta("dims", openvdb::Vec3IMetadata(openvdb::Vec3i(d.nx, d.ny, d.nz)));
  meta.insertMeta("temperature_units", openvdb::StringMetadata(kTemperatureUnits));
  meta.insertMeta("placement", openvdb::StringMetadata(format_placement(placement)));
  for (const auto& [key, value] : extra_metadata)
    meta.insertMeta(key, openvdb::StringMetadata(value));
  return meta;
}

// One float grid of `spec` holding `values` (dims.count() floats, x fastest).
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

ChannelSummary summarise(const std::string& name, const std::string& units, const float* v,
                         std::size_t count) {
  ChannelSummary s;
  s.name = name;
  s.units = units;
  const auto [lo, hi] = std::minmax_element(v, v + count);
  s.min = *lo;
  s.max = *hi;
  s.nonzero_voxels = static_cast<std::size_t>(count - std::count(v, v + count, 0.0f));
  return s;
}

}  // namespace

void write_cloud_keyframe(const std::filesystem::path& path, const VoxelGrid& grid, double time_s,
                          const std::map<std::string, std::string>& extra_metadata) {
  ensure_openvdb_initialized();
  const std::string file = path.string();
  check_time_and_metadata(file, time_s, extra_metadata);
  grid.validate(file);  // an invalid grid would only be refused by the reader

  openvdb::MetaMap meta = common_metadata(kFormSpectral, time_s, grid.wavelengths_um(), grid.dims(),
                                          grid.placement(), extra_metadata);
  meta.insertMeta("coefficient_units", openvdb::StringMetadata(kCoefficientUnits));
  const openvdb::math::Transform::Ptr xf = placement_to_transform(grid.placement());
  const std::vector<GridSpec> layout = spectral_layout(grid.wavelengths_um());
  openvdb::GridPtrVec grids;
  for (int c = 0; c < grid.channel_count(); ++c)
    grids.push_back(make_float_grid(layout[c], grid.channel(c), grid.dims(), *xf));
  write_keyframe_file(path, grids, meta);
}

void write_species_keyframe(const std::filesystem::path& path, const SpeciesCloud& cloud,
                            double time_s,
                            const std::map<std::string, std::string>& extra_metadata) {
  ensure_openvdb_initialized();
  const std::string file = path.string();
  check_time_and_metadata(file, time_s, extra_metadata);
  validate_species_cloud(cloud, file);  // an invalid cloud would only be refused by the reader

  openvdb::MetaMap meta = common_metadata(kFormSpecies, time_s, cloud.wavelengths_um, cloud.dims,
                                          cloud.placement, extra_metadata);
  meta.insertMeta("concentration_units", openvdb::StringMetadata(kConcentrationUnits));
  meta.insertMeta("species_count", openvdb::Int32Metadata(static_cast<int>(cloud.species.size())));
  meta.insertMeta("species_optics", openvdb::StringMetadata(format_species_optics(cloud.species)));
  const openvdb::math::Transform::Ptr xf = placement_to_transform(cloud.placement);
  const std::vector<GridSpec> layout = species_layout(cloud.species);
  openvdb::GridPtrVec grids;
  for (std::size_t s = 0; s < cloud.species.size(); ++s)
    grids.push_back(
        make_float_grid(layout[s], cloud.concentration_g_m3[s].data(), cloud.dims, *xf));
  grids.push_back(make_float_grid(layout.back(), cloud.temperature_k.data(), cloud.dims, *xf));
  write_keyframe_file(path, grids, meta);
}

CloudKeyframe read_cloud_keyframe(const std::filesystem::path& path) {
  return read_keyframe(path, /*keep_species=*/false).keyframe;
}

KeyframeInfo inspect_cloud_keyframe(const std::filesystem::path& path) {
  ReadResult r = read_keyframe(path, /*keep_species=*/true);
  const VoxelGrid& grid = *r.keyframe.grid;
  KeyframeInfo info;
  info.file = path;
  std::error_code ec;
  info.file_bytes = std::filesystem::file_size(path, ec);
  info.form = r.form;
  info.dims = grid.dims();
  info.wavelengths_um = grid.wavelengths_um();
  info.placement = grid.placement();
  info.world_bounds_m = grid.world_bounds();
  info.time_s = r.keyframe.time_s;
  info.memory_bytes = grid.memory_bytes();
  const std::size_t count = grid.dims().count();
  const std::vector<GridSpec> layout = spectral_layout(grid.wavelengths_um());
  for (int c = 0; c < grid.channel_count(); ++c)
    info.channels.push_back(summarise(layout[c].name, layout[c].units, grid.channel(c), count));
  if (r.species) {
    const SpeciesCloud& cloud = *r.species;
    info.compact_bytes = cloud.memory_bytes();
    for (std::size_t s = 0; s < cloud.species.size(); ++s)
      info.species.push_back(
          {cloud.species[s],
           summarise(species_concentration_name(static_cast<int>(s)), kConcentrationUnits,
                     cloud.concentration_g_m3[s].data(), count)});
  }
  for (auto it = r.file_metadata->beginMeta(); it != r.file_metadata->endMeta(); ++it)
    info.metadata[it->first] = it->second ? it->second->str() : std::string();
  return info;
}

}  // namespace obscura
