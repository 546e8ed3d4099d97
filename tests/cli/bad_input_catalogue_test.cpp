// The catalogue of bad inputs (issue 16): every subcommand and file type fed
// what a careless or hostile user might give it. Each case asserts the exit
// status (1 bad input, 64 bad command line; never a crash, never 2), that the
// message carries the "obscura: error:" prefix and names the file and the
// field, and that nothing is left under the output name.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
#include <vector>

#include "obscura/io/vdb_keyframe.h"
#include "obscura/medium/gaussian_puff.h"
#include "support/cli_runner.h"
#include "support/temp_dir_test.h"
#include "support/test_puff.h"
#include "support/tool_vdb.h"

namespace fs = std::filesystem;

namespace obscura {
namespace {

class Catalogue;

struct BadInput {
  std::string name;
  // Writes the case's files into the scratch folder and returns the arguments.
  std::function<std::string(Catalogue&)> setup;
  int status;
  // Every one must appear in stderr.
  std::vector<std::string> expected;
  // Relative to the scratch folder: must not exist afterwards ("" = none).
  std::string output = "out";
};

class Catalogue : public testing::TempDirTest, public ::testing::WithParamInterface<BadInput> {
 public:
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return path(name);
  }
  std::string puff(const std::string& name = "puff.vdb") {
    const GaussianPuffSpec spec = testing::small_puff_spec();
    write_cloud_keyframe(dir_ / name, make_gaussian_puff(spec), 0.0);
    return path(name);
  }
  // The puff cut to `bytes` (negative: that many bytes short of the whole).
  std::string cut_puff(long long bytes) {
    const std::string p = puff("cut.vdb");
    const auto size = static_cast<long long>(fs::file_size(p));
    fs::resize_file(p, static_cast<std::uintmax_t>(bytes < 0 ? size + bytes : bytes));
    return p;
  }
  static nlohmann::json scene(const std::string& cloud = "") {
    nlohmann::json s = {{"sensors",
                         {{{"name", "ir"},
                           {"position", {0, -30, 3}},
                           {"look_at", {0, 0, 3}},
                           {"fov_deg", 30},
                           {"width", 24},
                           {"height", 16},
                           {"bands", {"mwir", "lwir"}}}}},
                        {"surfaces", {{{"type", "ground"}, {"temperature", 290}}}},
                        {"sky", {{"temperature", 250}}}};
    if (!cloud.empty()) s["clouds"] = {{{"type", "vdb"}, {"file", cloud}}};
    return s;
  }
  // The scene's compact text with `from` replaced by `to` (once).
  std::string scene_text(const std::string& from, const std::string& to,
                         const nlohmann::json& s = scene()) {
    std::string text = s.dump();
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from << " not in " << text;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
  }
  std::string render(const std::string& scene_file, const std::string& extra = "") {
    return "render " + scene_file + " -o " + path("out") + extra;
  }
  std::string render_json(const nlohmann::json& s, const std::string& extra = "") {
    return render(write("scene.json", s.dump(2)), extra);
  }
  std::string render_text(const std::string& text, const std::string& extra = "") {
    return render(write("scene.json", text), extra);
  }
  std::string mesh_scene(const std::string& obj_name) {
    nlohmann::json s = scene();
    s["surfaces"].push_back(
        {{"type", "mesh"}, {"name", "tank"}, {"file", obj_name}, {"temperature", 300}});
    return write("scene.json", s.dump(2));
  }
  static constexpr const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  // Another tool's VDB file (support/tool_vdb.h): a density grid named
  // `density_name` beside temperature and velocity grids, on `xf`.
  std::string tool_vdb(const std::string& name, const std::string& density_name = "density",
                       openvdb::math::Transform::Ptr xf = testing::tool_transform()) {
    const openvdb::CoordBBox box(openvdb::Coord(0), openvdb::Coord(3));
    const auto value = [](int, int, int) { return 0.5f; };
    testing::write_tool_vdb(dir_ / name, {testing::tool_grid(density_name, xf, box, value),
                                          testing::tool_grid("temperature", xf, box, value),
                                          testing::tool_velocity(xf, box)});
    return path(name);
  }
  // A scene whose cloud is a vdb-density cloud of `file` (more keys in `extra`).
  std::string render_density(const std::string& file,
                             const nlohmann::json& extra = nlohmann::json::object()) {
    nlohmann::json cloud = {{"type", "vdb-density"},
                            {"file", file},
                            {"material", "soot"},
                            {"wavelengths_um", {4, 10}},
                            {"density_scale", 2}};
    cloud.update(extra);
    nlohmann::json s = scene();
    s["clouds"] = {cloud};
    return render_json(s);
  }
};

std::vector<BadInput> catalogue() {
  using C = Catalogue;
  std::vector<BadInput> t;
  auto add = [&](std::string name, std::function<std::string(C&)> setup, int status,
                 std::vector<std::string> expected, std::string output = "out") {
    t.push_back(
        {std::move(name), std::move(setup), status, std::move(expected), std::move(output)});
  };

  // ---- scene files: the path itself --------------------------------------
  add("SceneMissing", [](C& c) { return c.render(c.path("none.json")); }, 1,
      {"none.json", "no such file"});
  add("SceneIsAFolder",
      [](C& c) {
        fs::create_directory(c.path("scene.json"));
        return c.render(c.path("scene.json"));
      },
      1, {"scene.json", "is a folder, expected a JSON file"});
  add("SceneEmpty", [](C& c) { return c.render_text(""); }, 1,
      {"scene.json", "line 1 column 1", "invalid JSON"});
  add("SceneSyntaxError", [](C& c) { return c.render_text("{\n  \"sensors\": [\n}"); }, 1,
      {"scene.json", "line 3 column 1", "invalid JSON"});
  add("SceneBinaryGarbage",
      [](C& c) { return c.render_text(std::string("\x89PNG\r\n\x1a\n\0\0", 10)); }, 1,
      {"scene.json", "line 1", "invalid JSON"});
  add("SceneTopLevelArray", [](C& c) { return c.render_text("[1, 2]"); }, 1,
      {"scene.json", "/: expected a JSON object, found array"});

  // ---- scene files: JSON the DOM parser accepted silently or crashed on --
  add("SceneNested100000Deep",
      [](C& c) { return c.render_text(std::string(100000, '[') + std::string(100000, ']')); }, 1,
      {"scene.json", "nested more than 256 levels"});
  add("SceneDuplicateKey",
      [](C& c) { return c.render_text(c.scene_text("\"width\":24", "\"width\":24,\"width\":25")); },
      1, {"scene.json", "/sensors/0/width", "duplicate key"});
  add("SceneDuplicateTopLevelKey",
      [](C& c) { return c.render_text(c.scene_text("\"sky\":", "\"sky\":{},\"sky\":")); }, 1,
      {"scene.json", "/sky", "duplicate key"});
  add("SceneNumberOverflow1e999",
      [](C& c) { return c.render_text(c.scene_text("\"fov_deg\":30", "\"fov_deg\":1e999")); }, 1,
      {"scene.json", "/sensors/0/fov_deg", "1e999", "outside the range of a double"});
  add("SceneNegativeOverflow",
      [](C& c) {
        return c.render_text(c.scene_text("\"temperature\":250", "\"temperature\":-2e400"));
      },
      1, {"scene.json", "/sky/temperature", "outside the range of a double"});
  add("SceneNaNLiteral",
      [](C& c) { return c.render_text(c.scene_text("\"fov_deg\":30", "\"fov_deg\":NaN")); }, 1,
      {"scene.json", "line 1 column", "invalid JSON"});
  add("SceneInfinityLiteral",
      [](C& c) { return c.render_text(c.scene_text("\"fov_deg\":30", "\"fov_deg\":Infinity")); }, 1,
      {"scene.json", "line 1 column", "invalid JSON"});
  add("SceneIntegerBeyondInt64",
      [](C& c) {
        return c.render_text(c.scene_text("\"width\":24", "\"width\":18446744073709551615"));
      },
      1, {"scene.json", "/sensors/0/width", "out of range"});
  add("SceneIntegerBeyondUint64",
      [](C& c) {
        return c.render_text(c.scene_text("\"width\":24", "\"width\":99999999999999999999"));
      },
      1, {"scene.json", "/sensors/0/width", "expected an integer"});

  // ---- scene files: fields -------------------------------------------------
  add("SceneMisspeltKey", [](C& c) { return c.render_text(c.scene_text("\"sky\":", "\"skye\":")); },
      1, {"scene.json", "/skye", "unknown field"});
  add("SceneNoSensors", [](C& c) { return c.render_text("{}"); }, 1,
      {"scene.json", "/sensors", "missing required field"});
  add("SceneSensorsNotAnArray", [](C& c) { return c.render_text("{\"sensors\": 3}"); }, 1,
      {"scene.json", "/sensors", "expected an array"});
  add("SceneWidthNotAnInteger",
      [](C& c) { return c.render_text(c.scene_text("\"width\":24", "\"width\":\"24\"")); }, 1,
      {"scene.json", "/sensors/0/width", "expected an integer"});
  add("SceneWidthZero",
      [](C& c) { return c.render_text(c.scene_text("\"width\":24", "\"width\":0")); }, 1,
      {"scene.json", "/sensors/0/width", "must lie in [1, 16384]"});
  add("SceneUnknownBand",
      [](C& c) { return c.render_text(c.scene_text("\"mwir\"", "\"ultraviolet\"")); }, 1,
      {"scene.json", "/sensors/0/bands/0"});
  add("SceneSunWithoutScattering",
      [](C& c) {
        nlohmann::json s = C::scene();
        s["sun"] = {{"elevation_deg", 30}};
        return c.render_json(s);
      },
      1, {"scene.json", "/sun"});
  add("SceneCloudFileMissing", [](C& c) { return c.render_json(C::scene("nowhere.vdb")); }, 1,
      {"scene.json", "/clouds/0/file", "no such file"});

  // ---- memory limits -------------------------------------------------------
  add("ImageLargerThanMaxMemory",
      [](C& c) { return c.render_json(C::scene(), " --max-memory 4kB"); }, 1,
      {"scene.json", "/sensors/0/bands", "a 24x16 image with 2 bands needs",
       "the limit set by --max-memory"});
  add("ImageLargerThanSceneMaxMemory",
      [](C& c) {
        nlohmann::json s = C::scene();
        s["max_memory"] = "4kB";
        return c.render_json(s);
      },
      1, {"scene.json", "/sensors/0/bands", "needs", "the scene's max_memory"});
  add("SceneMaxMemoryNotASize",
      [](C& c) {
        nlohmann::json s = C::scene();
        s["max_memory"] = "plenty";
        return c.render_json(s);
      },
      1, {"scene.json", "/max_memory", "'plenty' is not a memory size"});
  add("MaxMemoryOptionNotASize",
      [](C& c) { return c.render_json(C::scene(), " --max-memory lots"); }, 1,
      {"--max-memory", "'lots' is not a memory size"});
  add("GridLargerThanMaxMemory",
      [](C& c) { return c.render_json(C::scene(c.puff()), " --max-memory 64kB"); }, 1,
      {"puff.vdb", "grid sigma_a_000", "its OpenVDB tree needs", "--max-memory"});
  add("PhotonsLargerThanMaxMemory",
      [](C& c) {
        nlohmann::json s = C::scene();
        s["render"] = {{"method", "photonmap"}, {"photon_map", {{"photons", 2000000000}}}};
        return c.render_json(s, " --max-memory 1GiB");
      },
      1, {"scene.json", "/render/photon_map/photons", "needs", "--max-memory"});

  // ---- VDB keyframes -------------------------------------------------------
  add("VdbCutTo100Bytes", [](C& c) { return c.render_json(C::scene(c.cut_puff(100))); }, 1,
      {"cut.vdb", "truncated"});
  add("VdbCutTo400Bytes", [](C& c) { return c.render_json(C::scene(c.cut_puff(400))); }, 1,
      {"cut.vdb", "truncated"});
  add("VdbCutInHalf",
      [](C& c) {
        c.puff("whole.vdb");
        return c.render_json(
            C::scene(c.cut_puff(static_cast<long long>(fs::file_size(c.path("whole.vdb")) / 2))));
      },
      1, {"cut.vdb", "truncated"});
  add("VdbOneByteShort", [](C& c) { return c.render_json(C::scene(c.cut_puff(-1))); }, 1,
      {"cut.vdb", "truncated"});
  add("VdbIsText",
      [](C& c) {
        c.write("text.vdb", "this is not a VDB file\n");
        return c.render_json(C::scene("text.vdb"));
      },
      1, {"text.vdb", "not an OpenVDB file"});
  add("VdbIsAFolder",
      [](C& c) {
        fs::create_directory(c.path("dir.vdb"));
        return c.render_json(C::scene("dir.vdb"));
      },
      1, {"dir.vdb", "is a folder, expected a cloud keyframe file"});

  // ---- other tools' VDB files (vdb-density clouds) ---------------------------
  add("VdbDensityMissingGrid",
      [](C& c) { return c.render_density(c.tool_vdb("explosion.vdb", "smoke")); }, 1,
      {"explosion.vdb: density: no grid of that name", "smoke, temperature, vel",
       "\"density_grid\""});
  add("VdbDensityWrongGridType",
      [](C& c) {
        return c.render_density(c.tool_vdb("explosion.vdb"), {{"density_grid", "vel"}});
      },
      1, {"explosion.vdb: vel: grid holds vec3s values, expected a float grid"});
  add("VdbDensityNonUniformVoxels",
      [](C& c) {
        openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
        m(2, 2) = 3.0;
        return c.render_density(c.tool_vdb("stretched.vdb", "density",
                                           openvdb::math::Transform::createLinearTransform(m)));
      },
      1, {"stretched.vdb: density: transform has non-uniform voxel size (1, 1, 3) m"});
  add("VdbDensityMissingFrame",
      [](C& c) {
        c.tool_vdb("smoke_0001.vdb");
        c.tool_vdb("smoke_0003.vdb");
        return c.render_density("smoke_####.vdb", {{"frame_rate_hz", 24}});
      },
      1, {"scene.json: /clouds/0/file: frame 2 of the sequence is missing", "smoke_0002.vdb"});
  add("VdbDensityTruncated",
      [](C& c) {
        const std::string p = c.tool_vdb("cut.vdb");
        fs::resize_file(p, fs::file_size(p) - 7);
        return c.render_density("cut.vdb");
      },
      1, {"cut.vdb", "truncated"});
  add("VdbDensityScaleMissing",
      [](C& c) {
        nlohmann::json s = C::scene();
        s["clouds"] = {{{"type", "vdb-density"},
                        {"file", c.tool_vdb("explosion.vdb")},
                        {"material", "soot"},
                        {"wavelengths_um", {4, 10}}}};
        return c.render_json(s);
      },
      1, {"scene.json: /clouds/0/density_scale: missing required field"});
  add(
      "InfoOnTruncatedVdb", [](C& c) { return "info " + c.cut_puff(300); }, 1,
      {"cut.vdb", "truncated"}, "");

  // ---- OBJ meshes ----------------------------------------------------------
  add("ObjFaceIndexOverflow",
      [](C& c) {
        c.write("tank.obj", std::string(C::kTriangle) + "f 1 2 99999999999999\n");
        return c.render(c.mesh_scene("tank.obj"));
      },
      1, {"tank.obj", "line 4", "'99999999999999' is out of range"});
  add("ObjVertexNotFinite",
      [](C& c) {
        c.write("tank.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n");
        return c.render(c.mesh_scene("tank.obj"));
      },
      1, {"tank.obj", "line 2", "not finite"});
  add("ObjIndexBeyondVertices",
      [](C& c) {
        c.write("tank.obj", std::string(C::kTriangle) + "f 1 2 9\n");
        return c.render(c.mesh_scene("tank.obj"));
      },
      1, {"tank.obj", "line 4", "vertex index 9 is out of range"});
  add("ObjIsAFolder",
      [](C& c) {
        fs::create_directory(c.path("tank.obj"));
        return c.render(c.mesh_scene("tank.obj"));
      },
      1, {"/surfaces/1/file", "tank.obj", "is a folder"});

  // ---- cloud manifests -----------------------------------------------------
  add(
      "ManifestDuplicateKey",
      [](C& c) {
        c.puff();
        return "cloud-state " +
               c.write("cloud.json",
                       R"({"keyframes": [{"file": "puff.vdb", "time": 0, "time": 1}]})") +
               " --at 0";
      },
      1, {"cloud.json", "/keyframes/0/time", "duplicate key"}, "");
  add(
      "ManifestIsAFolder",
      [](C& c) {
        fs::create_directory(c.path("cloud.json"));
        return "cloud-state " + c.path("cloud.json") + " --at 0";
      },
      1, {"cloud.json", "is a folder"}, "");
  add(
      "ManifestTimeOverflow",
      [](C& c) {
        c.puff();
        return "cloud-state " +
               c.write("cloud.json", R"({"keyframes": [{"file": "puff.vdb", "time": 1e999}]})") +
               " --at 0";
      },
      1, {"cloud.json", "/keyframes/0/time", "outside the range of a double"}, "");

  // ---- prepare configurations ----------------------------------------------
  add("PrepareConfigMissing",
      [](C& c) { return "prepare " + c.path("none.json") + " -o " + c.path("out"); }, 1,
      {"none.json", "no such file"});
  add("PrepareConfigIsAFolder",
      [](C& c) {
        fs::create_directory(c.path("prep.json"));
        return "prepare " + c.path("prep.json") + " -o " + c.path("out");
      },
      1, {"prep.json", "is a folder"});
  add("PrepareConfigDuplicateKey",
      [](C& c) {
        return "prepare " + c.write("prep.json", R"({"source": "x", "source": "y"})") + " -o " +
               c.path("out");
      },
      1, {"prep.json", "/source", "duplicate key"});
  add("PrepareConfigDeep",
      [](C& c) {
        return "prepare " + c.write("prep.json", std::string(5000, '[') + std::string(5000, ']')) +
               " -o " + c.path("out");
      },
      1, {"prep.json", "nested more than 256"});
  // A netCDF signature and garbage after it: the classic header walk
  // (io/netcdf_classic_check.h) names the part, HDF5 the format.
  for (const auto& [name, magic, parts] :
       {std::tuple{"PrepareNetcdfClassicGarbage", std::string("CDF\x01", 4),
                   std::vector<std::string>{"c.nc", "dimensions", "the netCDF file is corrupt"}},
        std::tuple{"PrepareNetcdf4Garbage", std::string("\x89HDF\r\n\x1a\n", 8),
                   std::vector<std::string>{"c.nc", "netCDF-4 (HDF5)", "truncated or corrupt"}}})
    add(
        name,
        [magic = magic](C& c) {
          c.write("c.nc", magic + std::string(200, '\xab'));
          const std::string config = R"({"source": "netcdf", "netcdf": {"file": "c.nc",
              "concentration": "soot"}, "material": "fog_oil", "wavelengths_um": [0.55]})";
          return "prepare " + c.write("prep.json", config) + " -o " + c.path("out") + " --quiet";
        },
        1, parts);
  add("PrepareMaxMemoryNotASize",
      [](C& c) {
        return "prepare " + c.write("prep.json", "{}") + " -o " + c.path("out") +
               " --max-memory 12XB";
      },
      1, {"--max-memory", "not a memory size"});

  // ---- command lines (usage errors: 64) ------------------------------------
  add(
      "NoSubcommand", [](C&) { return std::string(); }, 64, {"subcommand"}, "");
  add(
      "UnknownSubcommand", [](C&) { return std::string("frobnicate"); }, 64, {"frobnicate"}, "");
  add("RenderThreadsNotANumber", [](C& c) { return c.render_json(C::scene(), " --threads two"); },
      64, {"--threads", "two"});
  add("RenderThreadsOutOfRange", [](C& c) { return c.render_json(C::scene(), " --threads 99999"); },
      64, {"--threads"});
  add("RenderUnknownOption", [](C& c) { return c.render_json(C::scene(), " --frobnicate"); }, 64,
      {"--frobnicate"});
  add("RenderWithoutOutput",
      [](C& c) { return "render " + c.write("scene.json", C::scene().dump()); }, 64, {"--output"});
  add("RenderAtNotANumber", [](C& c) { return c.render_json(C::scene(), " --at soon"); }, 64,
      {"--at", "soon"});
  add(
      "ValidateTauNotANumber", [](C&) { return std::string("validate slab --tau thick"); }, 64,
      {"--tau", "thick"}, "");
  add(
      "ValidateUnknownOption", [](C&) { return std::string("validate slab --tau-x 1"); }, 64,
      {"--tau-x"}, "");

  // ---- command-line values the tool checks itself (1) ----------------------
  add("RenderTimeRangeWithZeroStep",
      [](C& c) { return c.render_json(C::scene(), " --time 0:1:0"); }, 1, {"--time"});
  add(
      "ValidateMaxMemoryNotASize", [](C&) { return std::string("validate slab --max-memory 3XB"); },
      1, {"--max-memory"}, "");
  // mie reads its numbers itself (apps/obscura/option_parsing.h): bad input, 1.
  add(
      "MieSizeParameterNotANumber",
      [](C&) { return std::string("mie --size-parameter big --index 1.5"); }, 1,
      {"--size-parameter", "'big' is not a finite number"}, "");
  add(
      "RadianceBadBand", [](C&) { return std::string("radiance --temperature 300 --band 12:8"); },
      1, {"--band"}, "");
  return t;
}

TEST_P(Catalogue, FailsCleanlyNamingFileAndField) {
  const BadInput& c = GetParam();
  const std::string args = c.setup(*this);
  const testing::CliResult r = testing::run_cli(args, dir_);
  EXPECT_EQ(r.status, c.status) << args << "\n" << r.err;
  EXPECT_EQ(r.err.rfind("obscura: error: ", 0), 0u) << r.err;
  for (const std::string& part : c.expected)
    EXPECT_NE(r.err.find(part), std::string::npos) << "'" << part << "' not in: " << r.err;
  // One line of message (and for usage errors a hint), never pages of output.
  EXPECT_LT(r.err.size(), 2000u) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  if (!c.output.empty()) {
    const fs::path out = dir_ / c.output;
    EXPECT_TRUE(!fs::exists(out) || (fs::is_directory(out) && fs::is_empty(out)))
        << "left behind under " << out;
  }
}

INSTANTIATE_TEST_SUITE_P(BadInputs, Catalogue, ::testing::ValuesIn(catalogue()),
                         [](const ::testing::TestParamInfo<BadInput>& p) { return p.param.name; });

}  // namespace
}  // namespace obscura
