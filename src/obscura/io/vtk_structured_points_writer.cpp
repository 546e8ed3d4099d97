// The VTK legacy STRUCTURED_POINTS writer (io/vtk_structured_points.h).
#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <limits>
#include <string_view>
#include <vector>

#include "obscura/core/error.h"
#include "obscura/io/atomic_file.h"
#include "obscura/io/vtk_legacy_lexer.h"
#include "obscura/io/vtk_structured_points.h"

namespace obscura {
namespace {

using vtk_legacy::encode_name;

class OutFile {
 public:
  explicit OutFile(const std::filesystem::path& path) : path_(path) {
    f_ = std::fopen(path.c_str(), "wb");
    if (f_ == nullptr)
      throw Error(fmt::format("cannot open {}: {}", path.string(), std::strerror(errno)));
  }
  ~OutFile() {
    if (f_ != nullptr) std::fclose(f_);
  }
  OutFile(const OutFile&) = delete;
  OutFile& operator=(const OutFile&) = delete;
  void write(const void* data, std::size_t n) {
    if (std::fwrite(data, 1, n, f_) != n)
      throw Error(fmt::format("cannot write {}: {}", path_.string(), std::strerror(errno)));
  }
  void write(std::string_view s) { write(s.data(), s.size()); }
  void close() {
    const int rc = std::fclose(f_);
    f_ = nullptr;
    if (rc != 0)
      throw Error(fmt::format("cannot write {}: {}", path_.string(), std::strerror(errno)));
  }

 private:
  std::filesystem::path path_;
  std::FILE* f_ = nullptr;
};

void check_arrays(const std::string& file, const std::vector<VtkScalarArray>& arrays,
                  VtkDataLocation location) {
  if (arrays.empty()) throw InputError(file, "", "nothing to write: no arrays");
  const ScalarGrid* first = arrays.front().grid;
  for (std::size_t i = 0; i < arrays.size(); ++i) {
    const VtkScalarArray& a = arrays[i];
    const std::string field = a.name.empty() ? fmt::format("array {}", i) : a.name;
    if (a.name.empty()) throw InputError(file, field, "array name is empty");
    for (std::size_t j = 0; j < i; ++j)
      if (arrays[j].name == a.name) throw InputError(file, field, "two arrays have this name");
    if (a.grid == nullptr) throw InputError(file, field, "no grid");
    const ScalarGrid& g = *a.grid;
    if (g.dims.nx <= 0 || g.dims.ny <= 0 || g.dims.nz <= 0)
      throw InputError(
          file, field,
          fmt::format("dims {}x{}x{} must all be > 0", g.dims.nx, g.dims.ny, g.dims.nz));
    if (g.values.size() != g.dims.count())
      throw InputError(file, field,
                       fmt::format("{} values for a {}x{}x{} grid", g.values.size(), g.dims.nx,
                                   g.dims.ny, g.dims.nz));
    if (!(std::isfinite(g.placement.voxel_size_m) && g.placement.voxel_size_m > 0.0) ||
        !is_finite(g.placement.origin_m))
      throw InputError(file, field, "voxel size must be finite and > 0, origin finite");
    if (!(g.placement.rotation == Mat3::identity()))
      throw InputError(file, field,
                       "a rotated grid cannot be written as VTK STRUCTURED_POINTS (axis-aligned)");
    if (!(g.dims == first->dims) || !(g.placement.origin_m == first->placement.origin_m) ||
        g.placement.voxel_size_m != first->placement.voxel_size_m)
      throw InputError(file, field,
                       fmt::format("grid differs from that of '{}': one dataset has one grid",
                                   arrays.front().name));
    if (location == VtkDataLocation::kCells &&
        std::max({g.dims.nx, g.dims.ny, g.dims.nz}) == std::numeric_limits<int>::max())
      throw InputError(file, field, "dims too large for CELL_DATA (DIMENSIONS = dims + 1)");
  }
}

// Nine values a line, each in the shortest decimal form that reads back to
// the same float (fmt's default), written in pieces of about 1 MiB.
void write_ascii_values(OutFile& out, const std::vector<float>& v) {
  fmt::memory_buffer buf;
  for (std::size_t i = 0; i < v.size(); ++i) {
    fmt::format_to(std::back_inserter(buf), "{}{}", v[i],
                   (i % 9 == 8 || i + 1 == v.size()) ? '\n' : ' ');
    if (buf.size() > (1 << 20)) {
      out.write(buf.data(), buf.size());
      buf.clear();
    }
  }
  out.write(buf.data(), buf.size());
}

// Big-endian floats (the VTK legacy byte order), then a newline.
void write_binary_values(OutFile& out, const std::vector<float>& v) {
  std::vector<unsigned char> buf;
  buf.reserve(std::min<std::size_t>(v.size(), 1 << 18) * 4);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::uint32_t u = std::bit_cast<std::uint32_t>(v[i]);
    buf.push_back(static_cast<unsigned char>(u >> 24));
    buf.push_back(static_cast<unsigned char>(u >> 16));
    buf.push_back(static_cast<unsigned char>(u >> 8));
    buf.push_back(static_cast<unsigned char>(u));
    if (buf.size() >= (1u << 20)) {
      out.write(buf.data(), buf.size());
      buf.clear();
    }
  }
  out.write(buf.data(), buf.size());
  out.write("\n");
}

}  // namespace

void write_vtk_structured_points(const std::filesystem::path& path,
                                 const std::vector<VtkScalarArray>& arrays, VtkEncoding encoding,
                                 VtkDataLocation location) {
  const std::string file = path.string();
  check_arrays(file, arrays, location);
  const ScalarGrid& g = *arrays.front().grid;
  const double h = g.placement.voxel_size_m;
  const bool points = location == VtkDataLocation::kPoints;
  // Points sit at voxel centres; cells are the voxels (see the header).
  const Vec3 origin = points ? g.placement.origin_m + Vec3(h, h, h) * 0.5 : g.placement.origin_m;
  const int add = points ? 0 : 1;

  AtomicFile atomic(path);
  OutFile out(atomic.temp_path());
  out.write(
      fmt::format("# vtk DataFile Version 3.0\n"
                  "obscura scalar grid\n"
                  "{}\n"
                  "DATASET STRUCTURED_POINTS\n"
                  "DIMENSIONS {} {} {}\n"
                  "ORIGIN {} {} {}\n"
                  "SPACING {} {} {}\n"
                  "{} {}\n",
                  encoding == VtkEncoding::kAscii ? "ASCII" : "BINARY", g.dims.nx + add,
                  g.dims.ny + add, g.dims.nz + add, origin.x, origin.y, origin.z, h, h, h,
                  points ? "POINT_DATA" : "CELL_DATA", g.dims.count()));
  for (const VtkScalarArray& a : arrays) {
    out.write(fmt::format("SCALARS {} float 1\nLOOKUP_TABLE default\n", encode_name(a.name)));
    if (encoding == VtkEncoding::kAscii)
      write_ascii_values(out, a.grid->values);
    else
      write_binary_values(out, a.grid->values);
  }
  out.close();
  atomic.commit();
}

void write_vtk_frame(const std::filesystem::path& path, const ConcentrationFrame& frame,
                     VtkEncoding encoding, VtkDataLocation location) {
  std::vector<VtkScalarArray> arrays{{"concentration", &frame.concentration_g_m3}};
  if (frame.temperature_k) arrays.push_back({"temperature", &*frame.temperature_k});
  write_vtk_structured_points(path, arrays, encoding, location);
}

}  // namespace obscura
