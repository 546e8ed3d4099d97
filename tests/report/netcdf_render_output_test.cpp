// render.nc (report/netcdf_render_output.h) written by SequenceWriter for a
// tiny two-sensor sequence and read back with the netCDF-C library: the
// dimensions of each sensor, the CF attributes, every image equal bit for bit
// to the SensorImage (and the EXR) of the same frame, the target masks and
// metrics; a failed run keeps the file only when its frames are complete.
#include "obscura/report/netcdf_render_output.h"

#include <gtest/gtest.h>
#include <netcdf.h>

#include <cstring>
#include <fstream>

#include "obscura/core/version.h"
#include "obscura/io/exr_writer.h"
#include "obscura/report/sequence_output.h"
#include "support/input_error.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

namespace fs = std::filesystem;

// A homogeneous cloud half hiding a hot target box; two sensors of different
// sizes and bands ("tv-1" becomes the suffix tv_1); the path tracer, so that
// the images carry standard errors. Small enough to render in well under a
// second per frame.
nlohmann::json tiny_scene() {
  return nlohmann::json::parse(R"({
    "sensors": [
      {"name": "ir", "position": [0, -40, 3], "look_at": [0, 0, 1.5], "fov_deg": 20,
       "width": 12, "height": 8, "bands": ["mwir", "8:12"]},
      {"name": "tv-1", "position": [5, -40, 3], "look_at": [0, 0, 1.5], "fov_deg": 25,
       "width": 6, "height": 5, "bands": ["lwir"]}],
    "clouds": [{"type": "homogeneous", "min": [-1.5, -6, 0], "max": [0.5, -2, 4],
                "wavelengths_um": [4, 10], "sigma_a": [0.3, 0.2], "sigma_s": [0.2, 0.05],
                "g": [0.6, 0.4], "temperature": 300}],
    "surfaces": [{"type": "ground", "height": 0, "temperature": 288, "emissivity": 0.95},
                 {"type": "box", "min": [-2, 0, 0], "max": [2, 4, 2.5], "temperature": 330,
                  "target": true}],
    "sky": {"temperature": 250},
    "outputs": ["netcdf"],
    "render": {"method": "path-tracer", "samples_per_pixel": 2, "seed": 3, "threads": 2}
  })");
}

// Reads render.nc through the netCDF-C API; every failure fails the test.
class NcFile {
 public:
  explicit NcFile(const fs::path& path) {
    EXPECT_EQ(nc_open(path.c_str(), NC_NOWRITE, &id_), NC_NOERR) << path;
  }
  ~NcFile() {
    if (id_ >= 0) nc_close(id_);
  }
  int var(const std::string& name) const {
    int v = -1;
    EXPECT_EQ(nc_inq_varid(id_, name.c_str(), &v), NC_NOERR) << name;
    return v;
  }
  bool has_var(const std::string& name) const {
    int v = -1;
    return nc_inq_varid(id_, name.c_str(), &v) == NC_NOERR;
  }
  std::size_t dim(const std::string& name) const {
    int d = -1;
    std::size_t n = 0;
    EXPECT_EQ(nc_inq_dimid(id_, name.c_str(), &d), NC_NOERR) << name;
    EXPECT_EQ(nc_inq_dimlen(id_, d, &n), NC_NOERR) << name;
    return n;
  }
  std::vector<std::string> dims_of(const std::string& var_name) const {
    const int v = var(var_name);
    int n = 0;
    nc_inq_varndims(id_, v, &n);
    std::vector<int> ids(static_cast<std::size_t>(n));
    nc_inq_vardimid(id_, v, ids.data());
    std::vector<std::string> names;
    for (int d : ids) {
      char name[NC_MAX_NAME + 1] = {};
      nc_inq_dimname(id_, d, name);
      names.push_back(name);
    }
    return names;
  }
  // A text attribute of a variable ("" for the global attributes).
  std::string text(const std::string& var_name, const char* att) const {
    const int v = var_name.empty() ? NC_GLOBAL : var(var_name);
    std::size_t len = 0;
    if (nc_inq_attlen(id_, v, att, &len) != NC_NOERR) return "<missing>";
    std::string s(len, '\0');
    EXPECT_EQ(nc_get_att_text(id_, v, att, s.data()), NC_NOERR);
    return s;
  }
  std::vector<float> floats(const std::string& var_name, std::vector<std::size_t> start,
                            std::vector<std::size_t> count) const {
    std::size_t n = 1;
    for (std::size_t c : count) n *= c;
    std::vector<float> out(n);
    EXPECT_EQ(nc_get_vara_float(id_, var(var_name), start.data(), count.data(), out.data()),
              NC_NOERR)
        << var_name;
    return out;
  }
  std::vector<double> doubles(const std::string& var_name, std::size_t n) const {
    std::vector<double> out(n);
    EXPECT_EQ(nc_get_var_double(id_, var(var_name), out.data()), NC_NOERR) << var_name;
    return out;
  }
  std::vector<std::string> strings(const std::string& var_name, std::size_t n) const {
    std::vector<char*> p(n);
    EXPECT_EQ(nc_get_var_string(id_, var(var_name), p.data()), NC_NOERR) << var_name;
    std::vector<std::string> out(p.begin(), p.end());
    nc_free_string(n, p.data());
    return out;
  }
  int id() const { return id_; }

 private:
  int id_ = -1;
};

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// Files in `dir` whose names start with '.': AtomicFile temporaries.
int temporaries_in(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().front() == '.') ++n;
  return n;
}

class NetcdfRenderOutputTest : public testing::TempDirTest {
 protected:
  Provenance provenance() const {
    return make_provenance("obscura render scene.json -o out --format netcdf", 3, {});
  }
};

TEST_F(NetcdfRenderOutputTest, HoldsEveryFrameSensorAndBandAsRendered) {
  Scene scene = parse_scene(tiny_scene(), dir_ / "scene.json");
  const std::vector<double> times = {0.0, 0.5, 1.0};
  const Provenance prov = provenance();
  SequenceWriter writer(dir_, scene, times, true, prov, "scene.json");
  std::vector<RenderedFrame> frames;
  SequenceOptions options;
  options.on_frame = [&](const RenderedFrame& f) {
    writer.write_frame(f);
    frames.push_back(f);
  };
  const SequenceResult result = render_sequence(scene, times, options);
  writer.finish(result);
  const fs::path path = dir_ / "render.nc";
  ASSERT_TRUE(fs::is_regular_file(path));
  EXPECT_EQ(temporaries_in(dir_), 0);
  const auto& outputs = writer.summary()["outputs"];
  EXPECT_NE(std::find(outputs.begin(), outputs.end(), path.string()), outputs.end());

  const NcFile nc(path);
  // Dimensions: time shared, the rest per sensor.
  EXPECT_EQ(nc.dim("time"), 3u);
  EXPECT_EQ(nc.dim("band_ir"), 2u);
  EXPECT_EQ(nc.dim("y_ir"), 8u);
  EXPECT_EQ(nc.dim("x_ir"), 12u);
  EXPECT_EQ(nc.dim("band_tv_1"), 1u);
  EXPECT_EQ(nc.dim("y_tv_1"), 5u);
  EXPECT_EQ(nc.dim("x_tv_1"), 6u);
  EXPECT_EQ(nc.dims_of("radiance_ir"),
            (std::vector<std::string>{"time", "band_ir", "y_ir", "x_ir"}));
  EXPECT_EQ(nc.dims_of("transmittance_tv_1"),
            (std::vector<std::string>{"time", "band_tv_1", "y_tv_1", "x_tv_1"}));
  EXPECT_EQ(nc.dims_of("transmittance_mean_ir"), (std::vector<std::string>{"time", "band_ir"}));
  EXPECT_EQ(nc.dims_of("target_mask_tv_1"), (std::vector<std::string>{"y_tv_1", "x_tv_1"}));

  // CF attributes.
  EXPECT_EQ(nc.text("", "Conventions"), "CF-1.10");
  EXPECT_EQ(nc.text("", "source"), std::string("obscura ") + kVersion);
  EXPECT_EQ(nc.text("", "history"), prov.created_utc + ": " + prov.command_line);
  EXPECT_EQ(nc.text("", "provenance"), prov.to_string());
  EXPECT_EQ(nlohmann::json::parse(nc.text("", "scene")), scene.source);
  EXPECT_EQ(nc.text("", "run_status"), "complete");
  EXPECT_EQ(nc.text("", "method"), "path-tracer");
  EXPECT_EQ(nc.text("time", "units"), "s");
  EXPECT_EQ(nc.text("time", "axis"), "T");
  for (const std::string s : {"ir", "tv_1"}) {
    EXPECT_EQ(nc.text("radiance_" + s, "units"), "W m-2 sr-1") << s;
    EXPECT_EQ(nc.text("radiance_stderr_" + s, "units"), "W m-2 sr-1") << s;
    EXPECT_EQ(nc.text("transmittance_" + s, "units"), "1") << s;
    EXPECT_EQ(nc.text("apparent_temperature_" + s, "units"), "K") << s;
    EXPECT_EQ(nc.text("apparent_temperature_" + s, "standard_name"), "brightness_temperature");
    EXPECT_EQ(nc.text("band_min_um_" + s, "units"), "um") << s;
    EXPECT_EQ(nc.text("target_radiance_" + s, "units"), "W m-2 sr-1") << s;
    EXPECT_EQ(nc.text("delta_t_" + s, "units"), "K") << s;
    EXPECT_NE(nc.text("radiance_" + s, "long_name"), "<missing>") << s;
  }
  EXPECT_EQ(nc.text("radiance_tv_1", "sensor"), "tv-1");

  // Coordinates.
  EXPECT_EQ(nc.doubles("time", 3), times);
  EXPECT_EQ(nc.strings("band_ir", 2), (std::vector<std::string>{"mwir", "8:12"}));
  EXPECT_EQ(nc.doubles("band_min_um_ir", 2), (std::vector<double>{3, 8}));
  EXPECT_EQ(nc.doubles("band_max_um_ir", 2), (std::vector<double>{5, 12}));
  EXPECT_EQ(nc.doubles("band_centre_um_tv_1", 1), (std::vector<double>{10}));
  EXPECT_EQ(nc.doubles("x_tv_1", 6), (std::vector<double>{0, 1, 2, 3, 4, 5}));

  // Every image of every frame, bit for bit.
  ASSERT_EQ(frames.size(), 3u);
  int compared = 0;
  for (std::size_t f = 0; f < frames.size(); ++f)
    for (const SensorImage& image : frames[f].images) {
      const std::string s = netcdf_sensor_suffix(image.sensor);
      for (std::size_t b = 0; b < image.bands.size(); ++b) {
        const BandImage& band = image.bands[b];
        const std::vector<std::size_t> start{f, b, 0, 0},
            count{1, 1, static_cast<std::size_t>(image.height),
                  static_cast<std::size_t>(image.width)};
        EXPECT_TRUE(same_bits(nc.floats("radiance_" + s, start, count), band.radiance));
        EXPECT_TRUE(
            same_bits(nc.floats("radiance_stderr_" + s, start, count), band.radiance_stderr));
        EXPECT_TRUE(same_bits(nc.floats("transmittance_" + s, start, count), band.transmittance));
        EXPECT_TRUE(same_bits(nc.floats("apparent_temperature_" + s, start, count),
                              band.apparent_temperature));
        compared += 4;
      }
    }
  EXPECT_EQ(compared, 3 * (2 + 1) * 4);
  // … and the EXR of the same frame.
  const ExrImage exr = read_exr(dir_ / "ir_f0001.exr");
  EXPECT_TRUE(same_bits(nc.floats("radiance_ir", {1, 1, 0, 0}, {1, 1, 8, 12}),
                        exr.channels.at("8:12.radiance")));
  EXPECT_EQ(exr.double_attributes.at("obscura.time_s"), 0.5);

  // Target masks and metrics, as the sequence measured them.
  for (std::size_t i = 0; i < result.masks.size(); ++i) {
    const TargetMask& m = result.masks[i];
    const std::string s = netcdf_sensor_suffix(m.sensor);
    std::vector<std::uint8_t> labels(m.labels.size());
    ASSERT_EQ(nc_get_var_uchar(nc.id(), nc.var("target_mask_" + s), labels.data()), NC_NOERR);
    for (std::size_t p = 0; p < labels.size(); ++p)
      EXPECT_EQ(labels[p], static_cast<std::uint8_t>(m.labels[p])) << s << " pixel " << p;
    EXPECT_EQ(nc.text("target_mask_" + s, "flag_meanings"), "other target background");
  }
  std::vector<double> mean(3 * 2), delta_t(3 * 2);
  std::vector<int> pixels(3 * 2);
  ASSERT_EQ(nc_get_var_int(nc.id(), nc.var("target_pixels_ir"), pixels.data()), NC_NOERR);
  mean = nc.doubles("transmittance_mean_ir", 6);
  delta_t = nc.doubles("delta_t_ir", 6);
  std::size_t k = 0;
  for (const ScreeningMetrics& m : result.metrics) {
    if (m.sensor != "ir") continue;
    EXPECT_EQ(mean[k], m.transmittance_mean) << k;
    EXPECT_EQ(pixels[k], m.target_pixels) << k;
    EXPECT_EQ(delta_t[k], m.delta_t_k) << k;
    ++k;
  }
  EXPECT_EQ(k, 6u);
  EXPECT_GT(pixels[0], 0);
  const auto screening = nlohmann::json::parse(nc.text("", "screening"));
  EXPECT_EQ(screening["series"].size(), 3u);
}

TEST_F(NetcdfRenderOutputTest, WithoutTheFormatNoFileAndWithoutATargetNoMetrics) {
  auto doc = tiny_scene();
  doc.erase("outputs");
  Scene plain = parse_scene(doc, dir_ / "scene.json");
  SequenceWriter none(dir_ / "none", plain, {0.0}, false, provenance(), "scene.json");
  none.write_frame(render_frame(plain));
  none.finish(render_sequence(plain, {0.0}));
  EXPECT_FALSE(fs::exists(dir_ / "none" / "render.nc"));

  doc = tiny_scene();
  doc["surfaces"][1].erase("target");
  doc["render"]["method"] = "emission-absorption";
  doc["render"].erase("samples_per_pixel");
  Scene scene = parse_scene(doc, dir_ / "scene.json");
  SequenceWriter writer(dir_ / "out", scene, {0.0}, false, provenance(), "scene.json");
  SequenceOptions options;
  options.on_frame = [&](const RenderedFrame& f) { writer.write_frame(f); };
  writer.finish(render_sequence(scene, {0.0}, options));
  const NcFile nc(dir_ / "out" / "render.nc");
  EXPECT_EQ(nc.dim("time"), 1u);
  EXPECT_TRUE(nc.has_var("radiance_ir"));
  EXPECT_FALSE(nc.has_var("radiance_stderr_ir"));  // not a Monte Carlo method
  EXPECT_FALSE(nc.has_var("target_mask_ir"));
  EXPECT_FALSE(nc.has_var("transmittance_mean_ir"));
}

TEST_F(NetcdfRenderOutputTest, AFailedRunKeepsItsFirstFramesAndRecordsTheFailure) {
  Scene scene = parse_scene(tiny_scene(), dir_ / "scene.json");
  const std::vector<double> times = {0.0, 0.5, 1.0};
  SequenceWriter writer(dir_, scene, times, true, provenance(), "scene.json");
  for (std::size_t f = 0; f < 2; ++f) {
    stage_scene(scene, times[f]);
    writer.write_frame(render_frame(scene, f, times.size()));
  }
  writer.finish_failed("frame 2 failed");
  const fs::path path = dir_ / "render.nc";
  ASSERT_TRUE(fs::is_regular_file(path));
  EXPECT_EQ(temporaries_in(dir_), 0);
  const NcFile nc(path);
  EXPECT_EQ(nc.dim("time"), 2u);
  EXPECT_EQ(nc.doubles("time", 2), (std::vector<double>{0.0, 0.5}));
  EXPECT_EQ(nc.text("", "run_status"), "failed");
  EXPECT_EQ(nc.text("", "run_error"), "frame 2 failed");
  EXPECT_FALSE(nc.has_var("transmittance_mean_ir"));  // metrics come with a complete run only
  const auto summary = nlohmann::json::parse(std::ifstream(dir_ / "summary.json"));
  const auto& outputs = summary["outputs"];
  EXPECT_NE(std::find(outputs.begin(), outputs.end(), path.string()), outputs.end());
}

TEST_F(NetcdfRenderOutputTest, AFailedRunWhoseFramesAreNotTheFirstRemovesTheFile) {
  Scene scene = parse_scene(tiny_scene(), dir_ / "scene.json");
  const std::vector<double> times = {0.0, 0.5};
  SequenceWriter writer(dir_, scene, times, true, provenance(), "scene.json");
  stage_scene(scene, times[1]);
  writer.write_frame(render_frame(scene, 1, times.size()));  // frame 0 never came
  writer.finish_failed("frame 0 failed");
  EXPECT_FALSE(fs::exists(dir_ / "render.nc"));
  EXPECT_EQ(temporaries_in(dir_), 0);
}

TEST_F(NetcdfRenderOutputTest, SensorNamesThatWouldShareAVariableAreRefused) {
  auto doc = tiny_scene();
  doc["sensors"][0]["name"] = "tv.1";
  const Scene scene = parse_scene(doc, dir_ / "scene.json");
  const InputError e = testing::expect_input_error(
      [&] { SequenceWriter(dir_, scene, {0.0}, false, provenance(), "scene.json"); });
  EXPECT_EQ(e.field(), "/sensors/1/name");
  EXPECT_TRUE(testing::contains(e.detail(),
                                "sensors 'tv.1' and 'tv-1' would both name a "
                                "variable band_tv_1 in render.nc"))
      << e.what();
  EXPECT_FALSE(fs::exists(dir_ / "render.nc"));
  // Another sensor's prefix and suffix: "min_um_ir" would make band_min_um_ir too.
  doc = tiny_scene();
  doc["sensors"][1]["name"] = "min_um_ir";
  const Scene other = parse_scene(doc, dir_ / "scene.json");
  const InputError e2 = testing::expect_input_error(
      [&] { SequenceWriter(dir_, other, {0.0}, false, provenance(), "scene.json"); });
  EXPECT_TRUE(testing::contains(e2.detail(), "band_min_um_ir")) << e2.what();
  EXPECT_EQ(netcdf_sensor_suffix("seeker-2.b"), "seeker_2_b");
}

}  // namespace
}  // namespace obscura
