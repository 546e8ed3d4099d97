#include "obscura/io/vdb_keyframe_placement.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <system_error>
#include <vector>

#include "obscura/core/error.h"

namespace obscura::vdb_format {
namespace {

// Relative tolerance for "uniform" scale and "orthonormal" rotation in a
// transform read from a file: tools that store the map in single precision
// (or compose it from Euler angles) leave errors of ~1e-7, which are harmless.
constexpr double kTransformTolerance = 1e-6;

}  // namespace

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

GridPlacement transform_to_placement(const openvdb::math::Transform& xf, const std::string& file,
                                     const std::string& grid_name) {
  if (!xf.isLinear())
    throw InputError(file, grid_name,
                     fmt::format("transform is a non-linear '{}' map; obscura reads grids placed "
                                 "by a uniform scale, rotation and translation only",
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
                       fmt::format("transform has non-uniform voxel size ({}, {}, {}) m; obscura "
                                   "reads cubic voxels only",
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
                         "transform is sheared (its axes are not perpendicular); obscura reads "
                         "grids placed by a uniform scale, rotation and translation only");
    }
  const Mat3& R = p.rotation;
  const double det = R.m[0][0] * (R.m[1][1] * R.m[2][2] - R.m[1][2] * R.m[2][1]) -
                     R.m[0][1] * (R.m[1][0] * R.m[2][2] - R.m[1][2] * R.m[2][0]) +
                     R.m[0][2] * (R.m[1][0] * R.m[2][1] - R.m[1][1] * R.m[2][0]);
  if (det < 0.0)
    throw InputError(file, grid_name,
                     "transform mirrors the grid (negative determinant); obscura reads "
                     "proper rotations only");
  const Vec3 t(m(3, 0), m(3, 1), m(3, 2));
  p.origin_m = t - p.rotation * Vec3(0.5 * s, 0.5 * s, 0.5 * s);
  if (!is_finite(p.origin_m))
    throw InputError(file, grid_name, "transform translation is not finite");
  return p;
}

std::string format_placement(const GridPlacement& p) {
  std::string out =
      fmt::format("origin_m={:.17g},{:.17g},{:.17g};voxel_size_m={:.17g};rotation=", p.origin_m.x,
                  p.origin_m.y, p.origin_m.z, p.voxel_size_m);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      out += fmt::format("{}{:.17g}", r + c == 0 ? "" : ",", p.rotation.m[r][c]);
  return out;
}

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

bool placements_agree(const GridPlacement& a, const GridPlacement& b, const GridDims& d,
                      double tolerance) {
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 idx((corner & 1) ? d.nx : -1, (corner & 2) ? d.ny : -1, (corner & 4) ? d.nz : -1);
    if (length(a.index_to_world(idx) - b.index_to_world(idx)) > tolerance * a.voxel_size_m)
      return false;
  }
  return true;
}

}  // namespace obscura::vdb_format
