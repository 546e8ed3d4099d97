#include "obscura/io/exr_writer.h"

#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFloatAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <fmt/format.h>

#include <exception>
#include <set>

#include "obscura/core/error.h"
#include "obscura/io/atomic_file.h"

namespace obscura {
namespace {

void validate(const std::filesystem::path& path, int width, int height,
              const std::vector<ExrChannel>& channels) {
  const std::string file = path.string();
  if (width <= 0 || height <= 0) {
    throw InputError(file, "", fmt::format("EXR size must be positive, got {}x{}", width, height));
  }
  if (channels.empty()) throw InputError(file, "", "EXR needs at least one channel");
  const size_t count = static_cast<size_t>(width) * static_cast<size_t>(height);
  std::set<std::string> names;
  for (const ExrChannel& channel : channels) {
    if (channel.name.empty()) throw InputError(file, "", "EXR channel name is empty");
    if (!names.insert(channel.name).second) {
      throw InputError(file, channel.name, "duplicate EXR channel name");
    }
    if (channel.pixels.size() != count) {
      throw InputError(file, channel.name,
                       fmt::format("channel has {} pixels, expected {}x{} = {}",
                                   channel.pixels.size(), width, height, count));
    }
  }
}

// Adds one attribute to `header`. A name clash with a built-in attribute
// (e.g. "channels") or with an attribute already added would make OpenEXR
// throw, or replace it, with a less clear message.
template <typename Attribute, typename Value>
void insert_attribute(Imf::Header& header, const std::filesystem::path& path,
                      const std::string& name, const Value& value) {
  if (name.empty()) throw InputError(path.string(), "", "EXR attribute name is empty");
  if (header.find(name) != header.end())
    throw InputError(path.string(), name, "EXR attribute name is reserved or given twice");
  header.insert(name, Attribute(value));
}

}  // namespace

void write_exr(const std::filesystem::path& path, int width, int height,
               const std::vector<ExrChannel>& channels,
               const std::map<std::string, std::string>& string_attributes,
               const std::map<std::string, double>& double_attributes,
               const std::map<std::string, int>& int_attributes) {
  validate(path, width, height, channels);
  AtomicFile out(path);
  try {
    Imf::Header header(width, height, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y,
                       Imf::ZIP_COMPRESSION);
    for (const auto& [name, value] : string_attributes)
      insert_attribute<Imf::StringAttribute>(header, path, name, value);
    for (const auto& [name, value] : double_attributes)
      insert_attribute<Imf::DoubleAttribute>(header, path, name, value);
    for (const auto& [name, value] : int_attributes)
      insert_attribute<Imf::IntAttribute>(header, path, name, value);
    Imf::FrameBuffer frame;
    const size_t x_stride = sizeof(float);
    const size_t y_stride = sizeof(float) * static_cast<size_t>(width);
    for (const ExrChannel& channel : channels) {
      header.channels().insert(channel.name, Imf::Channel(Imf::FLOAT));
      // OpenEXR only reads through the slice; the cast drops const for its API.
      frame.insert(
          channel.name,
          Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(channel.pixels.data())),
                     x_stride, y_stride));
    }
    Imf::OutputFile file(out.temp_path().c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(height);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(fmt::format("cannot write EXR {}: {}", path.string(), e.what()));
  }
  // OutputFile is closed (scope left) before the rename, so the data is complete.
  out.commit();
}

ExrImage read_exr(const std::filesystem::path& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imath::Box2i window = header.dataWindow();
    ExrImage image;
    image.width = window.max.x - window.min.x + 1;
    image.height = window.max.y - window.min.y + 1;
    const size_t count = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);

    Imf::FrameBuffer frame;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
      std::vector<float>& pixels = image.channels[it.name()];
      pixels.assign(count, 0.0f);
      // Slice::Make handles a data window that does not start at (0, 0).
      frame.insert(it.name(), Imf::Slice::Make(Imf::FLOAT, pixels.data(), window));
    }
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);

    for (auto it = header.begin(); it != header.end(); ++it) {
      const Imf::Attribute& a = it.attribute();
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&a))
        image.string_attributes[it.name()] = s->value();
      else if (const auto* d = dynamic_cast<const Imf::DoubleAttribute*>(&a))
        image.double_attributes[it.name()] = d->value();
      else if (const auto* f = dynamic_cast<const Imf::FloatAttribute*>(&a))
        image.double_attributes[it.name()] = f->value();
      else if (const auto* i = dynamic_cast<const Imf::IntAttribute*>(&a))
        image.int_attributes[it.name()] = i->value();
    }
    return image;
  } catch (const std::exception& e) {
    throw InputError(path.string(), "", fmt::format("cannot read EXR: {}", e.what()));
  }
}

}  // namespace obscura
