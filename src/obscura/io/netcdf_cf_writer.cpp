// The CF writer (io/netcdf_cf.h): the series' checks, the dimensions,
// coordinate and data variables with their CF attributes, and the values.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <mutex>
#include <string_view>
#include <vector>

#include "obscura/core/error.h"
#include "obscura/io/atomic_file.h"
#include "obscura/io/netcdf_cf.h"
#include "obscura/io/netcdf_file.h"

namespace obscura {
namespace {

using netcdf_cf::NcHandle;

void check_series(const std::string& file, const ConcentrationSeries& s) {
  if (s.frames.empty()) throw InputError(file, "frames", "nothing to write: no frames");
  const ScalarGrid& g0 = s.frames.front().concentration_g_m3;
  const bool with_t = s.frames.front().temperature_k.has_value();
  for (std::size_t f = 0; f < s.frames.size(); ++f) {
    const ConcentrationFrame& fr = s.frames[f];
    const std::string field = fmt::format("frames[{}]", f);
    if (!std::isfinite(fr.time_s))
      throw InputError(file, field, fmt::format("time {} s is not finite", fr.time_s));
    if (f > 0 && !(fr.time_s > s.frames[f - 1].time_s))
      throw InputError(file, field,
                       fmt::format("time {} s is not after the previous frame's {} s", fr.time_s,
                                   s.frames[f - 1].time_s));
    if (fr.temperature_k.has_value() != with_t)
      throw InputError(file, field, "temperature must be present in every frame or in none");
    std::vector<const ScalarGrid*> grids{&fr.concentration_g_m3};
    if (fr.temperature_k) grids.push_back(&*fr.temperature_k);
    for (const ScalarGrid* g : grids) {
      const char* what = g == &fr.concentration_g_m3 ? "concentration" : "temperature";
      if (g->dims.nx < 2 || g->dims.ny < 2 || g->dims.nz < 2)
        throw InputError(file, field,
                         fmt::format("{} dims {}x{}x{}: at least 2 voxels per axis are needed "
                                     "so that the coordinates give the voxel size",
                                     what, g->dims.nx, g->dims.ny, g->dims.nz));
      if (g->values.size() != g->dims.count())
        throw InputError(file, field,
                         fmt::format("{} has {} values for {}x{}x{} voxels", what, g->values.size(),
                                     g->dims.nx, g->dims.ny, g->dims.nz));
      if (!(std::isfinite(g->placement.voxel_size_m) && g->placement.voxel_size_m > 0.0) ||
          !is_finite(g->placement.origin_m))
        throw InputError(file, field,
                         fmt::format("{}: voxel size must be finite and > 0, origin "
                                     "finite",
                                     what));
      if (!(g->placement.rotation == Mat3::identity()))
        throw InputError(file, field,
                         fmt::format("{}: a rotated grid cannot be written with x, y, "
                                     "z coordinate variables",
                                     what));
      if (!(g->dims == g0.dims) || !(g->placement.origin_m == g0.placement.origin_m) ||
          g->placement.voxel_size_m != g0.placement.voxel_size_m)
        throw InputError(file, field,
                         fmt::format("{} grid differs from frame 0's: a file has one grid", what));
    }
  }
}

class NcWriter {
 public:
  NcWriter(std::string file, int ncid) : file_(std::move(file)), ncid_(ncid) {}
  void check(int status, std::string_view doing) const {
    if (status != NC_NOERR)
      throw Error(fmt::format("cannot write {}: {}: {}", file_, doing, nc_strerror(status)));
  }
  void text(int varid, const char* name, const std::string& value) const {
    check(nc_put_att_text(ncid_, varid, name, value.size(), value.c_str()), name);
  }
  int ncid() const { return ncid_; }

 private:
  std::string file_;
  int ncid_;
};

// Variable ids of the file being written.
struct WrittenVariables {
  int time = 0, z = 0, y = 0, x = 0;
  std::array<int, 4> data_dims{};  // (time, z, y, x)
  int concentration = 0;
  int temperature = -1;  // -1: none
};

// Dimensions time (unlimited), z, y, x and their coordinate variables with
// their CF attributes.
WrittenVariables define_coordinates(const NcWriter& w, const GridDims& d) {
  const int nc = w.ncid();
  int dim_t = 0, dim_z = 0, dim_y = 0, dim_x = 0;
  w.check(nc_def_dim(nc, "time", NC_UNLIMITED, &dim_t), "time dimension");
  w.check(nc_def_dim(nc, "z", static_cast<std::size_t>(d.nz), &dim_z), "z dimension");
  w.check(nc_def_dim(nc, "y", static_cast<std::size_t>(d.ny), &dim_y), "y dimension");
  w.check(nc_def_dim(nc, "x", static_cast<std::size_t>(d.nx), &dim_x), "x dimension");

  WrittenVariables v;
  v.data_dims = {dim_t, dim_z, dim_y, dim_x};
  w.check(nc_def_var(nc, "time", NC_DOUBLE, 1, &dim_t, &v.time), "time variable");
  w.check(nc_def_var(nc, "z", NC_DOUBLE, 1, &dim_z, &v.z), "z variable");
  w.check(nc_def_var(nc, "y", NC_DOUBLE, 1, &dim_y, &v.y), "y variable");
  w.check(nc_def_var(nc, "x", NC_DOUBLE, 1, &dim_x, &v.x), "x variable");
  w.text(v.time, "standard_name", "time");
  w.text(v.time, "long_name", "time");
  w.text(v.time, "units", "s");
  w.text(v.time, "axis", "T");
  const struct {
    int var;
    const char* axis;
    const char* long_name;
  } spatial[] = {{v.x, "X", "x (east), voxel centre"},
                 {v.y, "Y", "y (north), voxel centre"},
                 {v.z, "Z", "z (up), voxel centre"}};
  for (const auto& sp : spatial) {
    w.text(sp.var, "long_name", sp.long_name);
    w.text(sp.var, "units", "m");
    w.text(sp.var, "axis", sp.axis);
  }
  w.text(v.z, "positive", "up");  // CF §4.3: required for a height-like axis
  return v;
}

// One time step per chunk (what the reader reads at once), at most ~16 MiB.
std::array<std::size_t, 4> time_step_chunk(const GridDims& d) {
  const std::size_t plane = static_cast<std::size_t>(d.nx) * static_cast<std::size_t>(d.ny) * 4;
  const std::size_t target = std::size_t{16} << 20;
  std::array<std::size_t, 4> chunk{1, 1, static_cast<std::size_t>(d.ny),
                                   static_cast<std::size_t>(d.nx)};
  if (plane <= target)
    chunk[1] = std::clamp<std::size_t>(target / plane, 1, static_cast<std::size_t>(d.nz));
  else
    chunk[2] = std::clamp<std::size_t>(target / (static_cast<std::size_t>(d.nx) * 4), 1,
                                       static_cast<std::size_t>(d.ny));
  return chunk;
}

// A float (time, z, y, x) variable, chunked and zlib-compressed.
int define_data(const NcWriter& w, const WrittenVariables& v,
                const std::array<std::size_t, 4>& chunk, const char* name, const char* units,
                const char* long_name, const char* standard_name) {
  const int nc = w.ncid();
  int id = 0;
  w.check(nc_def_var(nc, name, NC_FLOAT, 4, v.data_dims.data(), &id), name);
  w.check(nc_def_var_chunking(nc, id, NC_CHUNKED, chunk.data()), name);
  w.check(nc_def_var_deflate(nc, id, 1, 1, 4), name);
  w.text(id, "units", units);
  w.text(id, "long_name", long_name);
  if (standard_name != nullptr) w.text(id, "standard_name", standard_name);
  return id;
}

// The coordinate values and every frame's time and data.
void write_values(const NcWriter& w, const WrittenVariables& v, const ConcentrationSeries& s) {
  const int nc = w.ncid();
  const GridDims d = s.frames.front().concentration_g_m3.dims;
  const GridPlacement& p = s.frames.front().concentration_g_m3.placement;
  // Voxel centres: origin + h·(i + ½) (docs/formats.md, "Grid placement").
  const auto centres = [&](int n, double origin) {
    std::vector<double> c(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) c[i] = origin + p.voxel_size_m * (i + 0.5);
    return c;
  };
  w.check(nc_put_var_double(nc, v.x, centres(d.nx, p.origin_m.x).data()), "x values");
  w.check(nc_put_var_double(nc, v.y, centres(d.ny, p.origin_m.y).data()), "y values");
  w.check(nc_put_var_double(nc, v.z, centres(d.nz, p.origin_m.z).data()), "z values");
  for (std::size_t f = 0; f < s.frames.size(); ++f) {
    const ConcentrationFrame& fr = s.frames[f];
    const std::size_t one = 1;
    w.check(nc_put_vara_double(nc, v.time, &f, &one, &fr.time_s), "time values");
    // ScalarGrid values are x fastest: exactly C order over (z, y, x).
    const std::array<std::size_t, 4> start{f, 0, 0, 0};
    const std::array<std::size_t, 4> count{1, static_cast<std::size_t>(d.nz),
                                           static_cast<std::size_t>(d.ny),
                                           static_cast<std::size_t>(d.nx)};
    w.check(nc_put_vara_float(nc, v.concentration, start.data(), count.data(),
                              fr.concentration_g_m3.values.data()),
            "concentration values");
    if (v.temperature >= 0)
      w.check(nc_put_vara_float(nc, v.temperature, start.data(), count.data(),
                                fr.temperature_k->values.data()),
              "temperature values");
  }
}

void write_locked(const std::filesystem::path& path, const ConcentrationSeries& s) {
  const std::string file = path.string();
  const bool with_t = s.frames.front().temperature_k.has_value();
  const GridDims& d = s.frames.front().concentration_g_m3.dims;

  AtomicFile atomic(path);
  NcHandle h;
  {
    const int status = nc_create(atomic.temp_path().c_str(), NC_NETCDF4 | NC_CLOBBER, &h.id);
    if (status != NC_NOERR) {
      h.id = -1;
      throw Error(
          fmt::format("cannot create {}: {}", atomic.temp_path().string(), nc_strerror(status)));
    }
  }
  const NcWriter w(file, h.id);
  WrittenVariables v = define_coordinates(w, d);
  const std::array<std::size_t, 4> chunk = time_step_chunk(d);
  v.concentration =
      define_data(w, v, chunk, "concentration", "g m-3", "obscurant mass concentration", nullptr);
  if (with_t)
    v.temperature = define_data(w, v, chunk, "temperature", "K", "temperature", "air_temperature");
  w.text(NC_GLOBAL, "Conventions", "CF-1.8");
  w.text(NC_GLOBAL, "title", "obscurant concentration time series");
  w.text(NC_GLOBAL, "source", s.source.empty() ? std::string("obscura") : s.source);
  w.text(NC_GLOBAL, "history", "written by obscura");
  w.check(nc_enddef(h.id), "end of definitions");
  write_values(w, v, s);
  w.check(nc_close(h.release()), "close");
  atomic.commit();
}

}  // namespace

void write_netcdf_cf(const std::filesystem::path& path, const ConcentrationSeries& series) {
  check_series(path.string(), series);
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  write_locked(path, series);
}

}  // namespace obscura
