#include "obscura/sequence/frame_message.h"

#include <cstdint>

#include "obscura/core/byte_stream.h"
#include "obscura/core/check.h"
#include "obscura/film/sensor_image_rows.h"
#include "obscura/render/renderer.h"

namespace obscura {

std::string encode_frame(const RenderedFrame& frame) {
  ByteWriter out;
  out.put<std::uint64_t>(frame.index);
  out.put(frame.time_s);
  out.put(frame.staging_seconds);
  out.put<std::uint64_t>(frame.images.size());
  for (const SensorImage& image : frame.images) {
    out.put(image.stats);
    out.put_string(encode_image_rows(image));
  }
  return out.take();
}

RenderedFrame decode_frame(const std::string& bytes, const Scene& scene) {
  ByteReader in(bytes);
  RenderedFrame frame;
  frame.index = in.get<std::uint64_t>();
  frame.time_s = in.get<double>();
  frame.staging_seconds = in.get<double>();
  OBSCURA_CHECK_MSG(in.get<std::uint64_t>() == scene.sensors.size(),
                    "frame with another number of sensors than the scene");
  const bool monte_carlo = method_is_monte_carlo(scene.settings.method);
  for (const Sensor& sensor : scene.sensors) {
    SensorImage& image = frame.images.emplace_back(blank_sensor_image(sensor, monte_carlo));
    image.stats = in.get<RenderStats>();
    // decode_image_rows adds the counters the rows carry.
    image.stats.rays = image.stats.segments = image.stats.integrand_evals = 0;
    decode_image_rows(in.get_string(), image);
  }
  OBSCURA_CHECK(in.done());
  return frame;
}

}  // namespace obscura
