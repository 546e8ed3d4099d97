// The io layer in Python: a VoxelGrid written as a cloud keyframe (the same
// writer as `obscura make-puff` and `prepare`: atomic, validated), and EXR
// images read back as numpy arrays (the render outputs of the CLI).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <map>
#include <memory>
#include <string>

#include "bindings.h"
#include "numpy_view.h"
#include "obscura/io/exr_writer.h"
#include "obscura/io/vdb_keyframe.h"

namespace obscura::python {

void bind_io(py::module_& m) {
  m.def(
      "write_keyframe",
      [](const std::filesystem::path& path, const VoxelGrid& grid, double time_s,
         const std::map<std::string, std::string>& metadata) {
        py::gil_scoped_release release;  // compression and the write take a while
        write_cloud_keyframe(path, grid, time_s, metadata);
      },
      py::arg("path"), py::arg("grid"), py::kw_only(), py::arg("time_s") = 0.0,
      py::arg("metadata") = std::map<std::string, std::string>{},
      "Writes the grid as an OpenVDB cloud keyframe at time_s (s after activation), "
      "atomically; a scene refers to it as {\"type\": \"vdb\", \"file\": path}.");
  m.def(
      "read_exr",
      [](const std::filesystem::path& path) {
        auto image = std::make_shared<const ExrImage>(read_exr(path));
        py::dict channels;
        for (const auto& [name, pixels] : image->channels)
          channels[py::str(name)] =
              read_only_view<float, ExrImage>(pixels.data(), {image->height, image->width}, image);
        py::dict out;
        out["width"] = image->width;
        out["height"] = image->height;
        out["channels"] = channels;
        // Text attributes as str, numeric ones (obscura.time_s, band limits) as
        // float and int.
        py::dict attributes;
        for (const auto& [name, value] : image->string_attributes)
          attributes[py::str(name)] = value;
        for (const auto& [name, value] : image->double_attributes)
          attributes[py::str(name)] = value;
        for (const auto& [name, value] : image->int_attributes) attributes[py::str(name)] = value;
        out["attributes"] = attributes;
        return out;
      },
      py::arg("path"),
      "An EXR image: {width, height, channels: {name: (height, width) float32}, attributes}. "
      "obscura's images name channels BAND.radiance, BAND.transmittance, "
      "BAND.apparent_temperature, BAND.radiance_stderr.");
}

}  // namespace obscura::python
