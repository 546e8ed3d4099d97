#include "obscura/io/vdb_keyframe.h"

#include <fmt/format.h>
#include <openvdb/io/File.h>
#include <openvdb/math/Transform.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <system_error>

#include "obscura/core/error.h"
#include "obscura/io/atomic_file.h"

namespace obscura {
namespace {

using DenseXYZ = openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ>;

constexpr const char* kFormatName = "cloud-keyframe";
constexpr const char* kCoefficientUnits = "1/m";
constexpr const char* kTemperatureUnits = "K";
constexpr const char* kTransformGrid = "temperature";

// Relative tolerance for "uniform" scale and "orthonormal" rotation in a
// transform read from a file: tools that store the map in single precision
// (or compose it from Euler angles) leave errors of ~1e-7, which are harmless.
constexpr double kTransformTolerance = 1e-6;

// File-level metadata keys this format owns; extra_metadata must not use them.
const std::set<std::string>& reserved_keys() {
  static const std::set<std::string> keys = {
      "obscura_format",    "obscura_format_version", "time_s",
      "wavelengths_um",    "spectral_count",         "dims",
      "coefficient_units", "temperature_units",      "placement"};
  return keys;
}

// openvdb::initialize registers grid, map and metadata types; reading a file
// before it fails with "unregistered type" errors, and it is not thread-safe.
void ensure_openvdb_initialized() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

enum class ChannelKind { kSigmaA, kSigmaS, kG, kTemperature };

ChannelKind channel_kind(const VoxelGrid& grid, int c) {
  const int n = grid.spectral_count();
  if (c < n) return ChannelKind::kSigmaA;
  if (c < 2 * n) return ChannelKind::kSigmaS;
  if (c < 3 * n) return ChannelKind::kG;
  return ChannelKind::kTemperature;
}

const char* channel_units(ChannelKind kind) {
  switch (kind) {
    case ChannelKind::kSigmaA:
    case ChannelKind::kSigmaS:
      return kCoefficientUnits;
    case ChannelKind::kG:
      return "1";
    case ChannelKind::kTemperature:
      return kTemperatureUnits;
  }
  return "";
}

int channel_spectral_index(const VoxelGrid& grid, int c) {
  return channel_kind(grid, c) == ChannelKind::kTemperature ? -1 : c % grid.spectral_count();
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
  std::string out = fmt::format("origin_m={:.17g},{:.17g},{:.17g};voxel_size_m={:.17g};rotation=",
                                p.origin_m.x, p.origin_m.y, p.origin_m.z, p.voxel_size_m);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out += fmt::format("{}{:.17g}", r + c == 0 ? "" : ",", p.rotation.m[r][c]);
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
void check_grid_metadata(const openvdb::GridBase& g, const VoxelGrid& grid, int c,
                         const std::string& file) {
  const std::string name = grid.channel_name(c);
  if (auto u = g.getMetadata<openvdb::StringMetadata>("units")) {
    const char* want = channel_units(channel_kind(grid, c));
    if (u->value() != want)
      throw InputError(
          file, name + ".units",
          fmt::format("units '{}' but this channel must be in '{}'", u->value(), want));
  }
  const int k = channel_spectral_index(grid, c);
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
    if (d->value() != grid.wavelengths_um()[k])
      throw InputError(file, name + ".wavelength_um",
                       fmt::format("wavelength {} µm differs from wavelengths_um[{}] = {} µm",
                                   d->value(), k, grid.wavelengths_um()[k]));
  }
}

// Grid names of the form <prefix>NNN with NNN >= spectral_count mean the
// spectral_count metadata and the grids disagree.
void check_no_extra_spectral_grids(openvdb::io::File& f, int n, const std::string& file) {
  for (auto it = f.beginName(); it != f.endName(); ++it) {
    const std::string name = *it;
    for (const char* prefix : {"sigma_a_", "sigma_s_", "g_"}) {
      const std::string p(prefix);
      if (name.size() != p.size() + 3 || name.compare(0, p.size(), p) != 0) continue;
      int idx = 0;
      const auto [end, ec] =
          std::from_chars(name.data() + p.size(), name.data() + name.size(), idx);
      if (ec == std::errc() && end == name.data() + name.size() && idx >= n)
        throw InputError(file, name,
                         fmt::format("grid index {} is beyond spectral_count {}", idx, n));
    }
  }
}

struct ReadResult {
  CloudKeyframe keyframe;
  openvdb::MetaMap::Ptr file_metadata;
};

ReadResult read_keyframe(const std::filesystem::path& path) {
  ensure_openvdb_initialized();
  const std::string file = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(file, "",
                     std::filesystem::exists(path, ec) ? "is not a regular file" : "no such file");

  openvdb::io::File f(file);
  try {
    // No delayed loading: readGrid below then reads the voxel data at once, so
    // a truncated file fails there, where the error can name the grid, and not
    // later inside copyToDense's worker threads.
    f.open(/*delayLoad=*/false);
  } catch (const openvdb::Exception& e) {
    throw InputError(file, "", fmt::format("not a readable OpenVDB file ({})", e.what()));
  }

  ReadResult result;
  result.file_metadata = f.getMetadata();
  const MetaReader meta(*result.file_metadata, file);

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
  if (meta.get_string("coefficient_units") != kCoefficientUnits)
    throw InputError(file, "coefficient_units",
                     fmt::format("is '{}', expected '{}'", meta.get_string("coefficient_units"),
                                 kCoefficientUnits));
  if (meta.get_string("temperature_units") != kTemperatureUnits)
    throw InputError(file, "temperature_units",
                     fmt::format("is '{}', expected '{}'", meta.get_string("temperature_units"),
                                 kTemperatureUnits));

  const double time_s = meta.get_double("time_s");
  if (!(std::isfinite(time_s) && time_s >= 0.0))
    throw InputError(
        file, "time_s",
        fmt::format("time {} s must be finite and >= 0 (seconds after activation)", time_s));

  const long long spectral_count = meta.get_int("spectral_count");
  if (spectral_count <= 0 || spectral_count > 999)  // grid names carry 3 digits
    throw InputError(file, "spectral_count",
                     fmt::format("{} must be between 1 and 999", spectral_count));
  const int n = static_cast<int>(spectral_count);
  std::vector<double> wavelengths = parse_wavelengths(meta.get_string("wavelengths_um"), file);
  if (static_cast<long long>(wavelengths.size()) != spectral_count)
    throw InputError(file, "wavelengths_um",
                     fmt::format("lists {} wavelengths but spectral_count is {}",
                                 wavelengths.size(), spectral_count));

  const openvdb::Vec3i d = meta.get_vec3i("dims");
  const GridDims dims{d.x(), d.y(), d.z()};
  // Before reading any voxel data: refuse dims that overflow or exceed memory.
  VoxelGrid::checked_storage_bytes(dims, n, file);

  // Names, types and transforms first, from the grid headers only.
  check_no_extra_spectral_grids(f, n, file);
  // Same names as VoxelGrid::channel_name, needed before the grid exists.
  std::vector<std::string> names;
  for (int c = 0; c < 3 * n + 1; ++c)
    names.push_back(c < n       ? fmt::format("sigma_a_{:03d}", c)
                    : c < 2 * n ? fmt::format("sigma_s_{:03d}", c - n)
                    : c < 3 * n ? fmt::format("g_{:03d}", c - 2 * n)
                                : std::string("temperature"));
  std::vector<openvdb::GridBase::Ptr> headers;
  for (const std::string& name : names) {
    if (!f.hasGrid(name)) throw InputError(file, name, "grid is missing");
    openvdb::GridBase::Ptr h;
    try {
      h = f.readGridMetadata(name);
    } catch (const openvdb::Exception& e) {
      throw InputError(file, name, fmt::format("cannot read grid header ({})", e.what()));
    }
    if (!h->isType<openvdb::FloatGrid>())
      throw InputError(file, name,
                       fmt::format("grid has type {}, expected a float grid", h->type()));
    headers.push_back(h);
  }
  const openvdb::GridBase& reference = *headers.back();  // temperature
  const GridPlacement placement =
      transform_to_placement(reference.constTransform(), file, kTransformGrid);
  for (std::size_t c = 0; c + 1 < headers.size(); ++c)
    if (!(headers[c]->constTransform() == reference.constTransform()))
      throw InputError(file, names[c],
                       "grid transform differs from the 'temperature' grid's; all grids of a "
                       "keyframe must share one placement");

  // Prefer the exact placement written beside the transform, when it agrees with it.
  GridPlacement exact_placement = placement;
  if (auto m = result.file_metadata->getMetadata<openvdb::StringMetadata>("placement")) {
    const auto parsed = parse_placement(m->value());
    if (!parsed)
      throw InputError(file, "placement", fmt::format("'{}' is not a placement record", m->value()));
    if (!placements_agree(*parsed, placement, dims, 1e-6))
      throw InputError(file, "placement",
                       "disagrees with the grids' transform (the file was edited inconsistently)");
    exact_placement = *parsed;
  }
  auto grid = std::make_shared<VoxelGrid>(dims, exact_placement, std::move(wavelengths), file);
  for (int c = 0; c < grid->channel_count(); ++c)
    if (names[c] != grid->channel_name(c))  // the list above must mirror channel_name
      throw std::logic_error("vdb_keyframe: channel name mismatch for " + names[c]);
  for (int c = 0; c < grid->channel_count(); ++c) check_grid_metadata(*headers[c], *grid, c, file);

  const openvdb::CoordBBox bounds = dense_bbox(dims);
  for (int c = 0; c < grid->channel_count(); ++c) {
    const std::string& name = names[c];
    openvdb::FloatGrid::Ptr g;
    try {
      g = openvdb::gridPtrCast<openvdb::FloatGrid>(f.readGrid(name));
    } catch (const openvdb::Exception& e) {
      throw InputError(file, name, fmt::format("cannot read grid ({})", e.what()));
    }
    const openvdb::CoordBBox active = g->evalActiveVoxelBoundingBox();
    if (!active.empty() && !bounds.isInside(active))
      throw InputError(
          file, name,
          fmt::format("active voxels span [{},{},{}]..[{},{},{}], outside the grid "
                      "dims [0,0,0]..[{},{},{}]",
                      active.min().x(), active.min().y(), active.min().z(), active.max().x(),
                      active.max().y(), active.max().z(), dims.nx - 1, dims.ny - 1, dims.nz - 1));
    DenseXYZ dense(bounds, grid->channel(c));
    openvdb::tools::copyToDense(*g, dense);
  }
  f.close();
  grid->validate(file);
  result.keyframe = CloudKeyframe{std::move(grid), time_s};
  return result;
}

}  // namespace

void write_cloud_keyframe(const std::filesystem::path& path, const VoxelGrid& grid, double time_s,
                          const std::map<std::string, std::string>& extra_metadata) {
  ensure_openvdb_initialized();
  const std::string file = path.string();
  if (!(std::isfinite(time_s) && time_s >= 0.0))
    throw InputError(
        file, "time_s",
        fmt::format("time {} s must be finite and >= 0 (seconds after activation)", time_s));
  for (const auto& [key, value] : extra_metadata) {
    if (key.empty()) throw InputError(file, "metadata", "metadata names must not be empty");
    if (reserved_keys().count(key))
      throw InputError(file, key, "is a reserved cloud-keyframe metadata name");
  }
  grid.validate(file);  // an invalid grid would only be refused by the reader

  openvdb::MetaMap meta;
  meta.insertMeta("obscura_format", openvdb::StringMetadata(kFormatName));
  meta.insertMeta("obscura_format_version", openvdb::Int32Metadata(kCloudKeyframeFormatVersion));
  meta.insertMeta("time_s", openvdb::DoubleMetadata(time_s));
  meta.insertMeta("wavelengths_um",
                  openvdb::StringMetadata(format_wavelengths(grid.wavelengths_um())));
  meta.insertMeta("spectral_count", openvdb::Int32Metadata(grid.spectral_count()));
  const GridDims& d = grid.dims();
  meta.insertMeta("dims", openvdb::Vec3IMetadata(openvdb::Vec3i(d.nx, d.ny, d.nz)));
  meta.insertMeta("coefficient_units", openvdb::StringMetadata(kCoefficientUnits));
  meta.insertMeta("temperature_units", openvdb::StringMetadata(kTemperatureUnits));
  meta.insertMeta("placement", openvdb::StringMetadata(format_placement(grid.placement())));
  for (const auto& [key, value] : extra_metadata)
    meta.insertMeta(key, openvdb::StringMetadata(value));

  const openvdb::math::Transform::Ptr xf = placement_to_transform(grid.placement());
  const openvdb::CoordBBox bounds = dense_bbox(d);
  openvdb::GridPtrVec grids;
  for (int c = 0; c < grid.channel_count(); ++c) {
    const ChannelKind kind = channel_kind(grid, c);
    auto g = openvdb::FloatGrid::create(/*background=*/0.0f);
    g->setName(grid.channel_name(c));
    g->setTransform(xf->copy());
    g->setGridClass(kind == ChannelKind::kSigmaA || kind == ChannelKind::kSigmaS
                        ? openvdb::GRID_FOG_VOLUME
                        : openvdb::GRID_UNKNOWN);
    g->insertMeta("units", openvdb::StringMetadata(channel_units(kind)));
    const int k = channel_spectral_index(grid, c);
    if (k >= 0) {
      g->insertMeta("spectral_index", openvdb::Int32Metadata(k));
      g->insertMeta("wavelength_um", openvdb::DoubleMetadata(grid.wavelengths_um()[k]));
    }
    // Dense only reads through this pointer here (copyFromDense takes it const);
    // the const_cast is for Dense's constructor, which has no const overload.
    const DenseXYZ dense(bounds, const_cast<float*>(grid.channel(c)));
    // Tolerance 0: only exact zeros become inactive background, so every other
    // value is stored bit for bit.
    openvdb::tools::copyFromDense(dense, *g, 0.0f);
    grids.push_back(g);
  }

  AtomicFile out(path);
  try {
    openvdb::io::File f(out.temp_path().string());
    f.write(grids, meta);
    f.close();
  } catch (const openvdb::Exception& e) {
    throw Error(fmt::format("cannot write cloud keyframe {}: {}", file, e.what()));
  }
  out.commit();
}

CloudKeyframe read_cloud_keyframe(const std::filesystem::path& path) {
  return read_keyframe(path).keyframe;
}

KeyframeInfo inspect_cloud_keyframe(const std::filesystem::path& path) {
  ReadResult r = read_keyframe(path);
  const VoxelGrid& grid = *r.keyframe.grid;
  KeyframeInfo info;
  info.file = path;
  std::error_code ec;
  info.file_bytes = std::filesystem::file_size(path, ec);
  info.dims = grid.dims();
  info.wavelengths_um = grid.wavelengths_um();
  info.placement = grid.placement();
  info.world_bounds_m = grid.world_bounds();
  info.time_s = r.keyframe.time_s;
  info.memory_bytes = grid.memory_bytes();
  const std::size_t count = grid.dims().count();
  for (int c = 0; c < grid.channel_count(); ++c) {
    const float* v = grid.channel(c);
    ChannelSummary s;
    s.name = grid.channel_name(c);
    s.units = channel_units(channel_kind(grid, c));
    const auto [lo, hi] = std::minmax_element(v, v + count);
    s.min = *lo;
    s.max = *hi;
    s.nonzero_voxels = static_cast<std::size_t>(count - std::count(v, v + count, 0.0f));
    info.channels.push_back(std::move(s));
  }
  for (auto it = r.file_metadata->beginMeta(); it != r.file_metadata->endMeta(); ++it)
    info.metadata[it->first] = it->second ? it->second->str() : std::string();
  return info;
}

}  // namespace obscura
