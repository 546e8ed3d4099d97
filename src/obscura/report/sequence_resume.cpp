#include "obscura/report/sequence_resume.h"

#include <fmt/format.h>

#include <algorithm>

#include "obscura/core/error.h"
#include "obscura/io/exr_writer.h"
#include "obscura/io/json_reader.h"
#include "obscura/render/renderer.h"
#include "obscura/report/render_output.h"

namespace obscura {

std::vector<std::size_t> completed_frames(const std::filesystem::path& dir, const Scene& scene,
                                          const std::vector<double>& times_s,
                                          const Provenance& provenance) {
  const auto path = dir / "summary.json";
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return {};
  const std::string file = path.string();
  const nlohmann::json summary = read_json_file(file);
  const auto differs = [&](const std::string& field, const std::string& what) {
    return InputError(file, field,
                      what +
                          ": the run in this folder was another one; --resume continues only "
                          "the same run (remove the folder or choose another)");
  };
  if (!summary.is_object() || !summary.contains("provenance") || !summary.contains("times_s"))
    throw InputError(file, "", "is not the summary of an obscura render sequence");
  if (summary["times_s"] != nlohmann::json(times_s))
    throw differs("/times_s", "other frame times than --time gives");
  if (summary.value("scene", nlohmann::json()) != scene.source)
    throw differs("/scene", "made from another scene");
  const nlohmann::json& earlier = summary["provenance"];
  if (earlier.value("seed", std::uint64_t{0}) != provenance.seed)
    throw differs("/provenance/seed", "made with another seed");
  // Any input that changed may have changed the frames already done.
  nlohmann::json inputs = nlohmann::json::array();
  for (const InputHash& h : provenance.inputs)
    inputs.push_back({{"path", h.path}, {"sha256", h.sha256}});
  const nlohmann::json before = earlier.value("inputs", nlohmann::json::array());
  if (before != inputs) {
    std::string changed;
    for (const nlohmann::json& now : inputs)
      if (std::find(before.begin(), before.end(), now) == before.end())
        changed += (changed.empty() ? "" : ", ") + now["path"].get<std::string>();
    throw differs("/provenance/inputs",
                  "made from input files with other contents (" +
                      (changed.empty() ? std::string("another set of files") : changed) + ")");
  }
  std::vector<std::size_t> done;
  if (!summary.contains("failed")) {
    for (std::size_t f = 0; f < times_s.size(); ++f) done.push_back(f);
    return done;
  }
  for (const nlohmann::json& f :
       summary["failed"].value("frames_completed", nlohmann::json::array())) {
    if (!f.is_number_unsigned() || f.get<std::size_t>() >= times_s.size())
      throw InputError(file, "/failed/frames_completed", "lists a frame the sequence has not got");
    done.push_back(f.get<std::size_t>());
  }
  return done;
}

RenderedFrame read_completed_frame(const std::filesystem::path& dir, const Scene& scene,
                                   std::size_t index, double time_s) {
  RenderedFrame frame;
  frame.index = index;
  frame.time_s = time_s;
  const bool monte_carlo = method_is_monte_carlo(scene.settings.method);
  for (const Sensor& sensor : scene.sensors) {
    const auto path = dir / fmt::format("{}_f{:04d}.exr", file_safe_name(sensor.name), index);
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
      throw InputError(path.string(), "",
                       fmt::format("frame {} is recorded as complete but its file is missing: "
                                   "cannot resume",
                                   index));
    const ExrImage exr = read_exr(path);
    SensorImage image = blank_sensor_image(sensor, monte_carlo);
    if (exr.width != image.width || exr.height != image.height)
      throw InputError(path.string(), "",
                       fmt::format("is {}x{} px where sensor {} renders {}x{}: cannot resume",
                                   exr.width, exr.height, sensor.name, image.width, image.height));
    for (BandImage& b : image.bands) {
      const auto take = [&](const std::string& quantity, std::vector<float>& into) {
        const std::string channel = b.band.name() + "." + quantity;
        const auto it = exr.channels.find(channel);
        if (it == exr.channels.end())
          throw InputError(path.string(), channel, "no such channel: cannot resume");
        into = it->second;
      };
      take("radiance", b.radiance);
      take("transmittance", b.transmittance);
      take("apparent_temperature", b.apparent_temperature);
      if (monte_carlo) take("radiance_stderr", b.radiance_stderr);
    }
    frame.images.push_back(std::move(image));
  }
  return frame;
}

}  // namespace obscura
