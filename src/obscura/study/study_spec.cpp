#include "obscura/study/study_spec.h"

#include <fmt/format.h>

#include <cmath>

#include "obscura/core/error.h"
#include "obscura/core/time_steps.h"
#include "obscura/io/json_reader.h"
#include "obscura/io/provenance.h"

namespace obscura {
namespace {

constexpr std::size_t kMaxCases = 100000;

bool valid_name(const std::string& name) {
  if (name.empty() || name.size() > 64) return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

// The frames: {"start", "end", "step"} in seconds, as prepare's times_s.
std::vector<double> read_times(JsonObject& root) {
  JsonObject t = root.object("times_s");
  const double start = t.number("start"), end = t.number("end"), step = t.positive("step");
  t.finish();
  if (end < start) throw root.error("times_s", "needs start <= end");
  if (time_step_count(start, end, step) > 100000)
    throw root.error("times_s", "gives more than 100000 frames");
  return time_steps(start, end, step);
}

StudyAxis read_axis(const nlohmann::json& value, const std::string& file, const std::string& at,
                    const StudySpec& spec) {
  JsonObject o(value, file, at);
  StudyAxis axis;
  axis.name = o.string("name");
  if (!valid_name(axis.name))
    throw o.error("name", "'" + axis.name + "' must be 1–64 letters, digits or '_'");
  const std::string which = o.string("file");
  if (which == "prepare")
    axis.file = StudyAxis::File::kPrepare;
  else if (which == "scene")
    axis.file = StudyAxis::File::kScene;
  else
    throw o.error("file", "'" + which + "' is not one of prepare, scene");
  if (axis.file == StudyAxis::File::kPrepare && spec.prepare_path.empty())
    throw o.error("file", "the study has no \"prepare\" configuration to change");
  axis.path = o.string("path");
  nlohmann::json::json_pointer pointer;
  try {
    pointer = nlohmann::json::json_pointer(axis.path);
  } catch (const nlohmann::json::exception&) {
    throw o.error("path", "'" + axis.path + "' is not a JSON pointer (like /wind/speed_m_s)");
  }
  const nlohmann::json& base = axis.file == StudyAxis::File::kPrepare ? spec.prepare : spec.scene;
  const std::filesystem::path& base_file =
      axis.file == StudyAxis::File::kPrepare ? spec.prepare_path : spec.scene_path;
  if (axis.path.empty() || !base.contains(pointer))
    throw o.error("path", fmt::format("'{}' is not a value of {} (an axis changes a value the "
                                      "base file holds)",
                                      axis.path, base_file.string()));
  const nlohmann::json& values = o.array("values");
  if (values.empty()) throw o.error("values", "must list at least one value");
  for (const nlohmann::json& v : values) axis.values.push_back(v);
  if (o.has("labels")) {
    const nlohmann::json& labels = o.array("labels");
    if (labels.size() != values.size())
      throw o.error("labels",
                    fmt::format("has {} labels for {} values", labels.size(), values.size()));
    for (const nlohmann::json& l : labels) {
      if (!(l.is_number() || l.is_string()))
        throw o.error("labels", "labels must be numbers or strings");
      axis.labels.push_back(l);
    }
  } else {
    for (const nlohmann::json& v : values)
      axis.labels.push_back(v.is_number() || v.is_string() ? v : nlohmann::json(v.dump()));
  }
  o.finish();
  return axis;
}

// The scene's animated cloud a case's prepared cloud replaces.
void find_cloud(JsonObject& root, StudySpec& spec) {
  const std::string scene_file = spec.scene_path.string();
  const nlohmann::json* clouds = spec.scene.contains("clouds") ? &spec.scene["clouds"] : nullptr;
  std::vector<std::size_t> animated;
  if (clouds && clouds->is_array())
    for (std::size_t i = 0; i < clouds->size(); ++i)
      if ((*clouds)[i].is_object() && (*clouds)[i].value("type", "") == "animated")
        animated.push_back(i);
  if (root.has("cloud")) {
    spec.cloud = root.string("cloud");
    for (std::size_t i : animated)
      if ((*clouds)[i].value("name", "") == spec.cloud) {
        spec.cloud_index = i;
        return;
      }
    throw root.error("cloud",
                     fmt::format("{} has no animated cloud named '{}'", scene_file, spec.cloud));
  }
  if (animated.size() != 1)
    throw InputError(scene_file, "/clouds",
                     fmt::format("has {} animated clouds: the study's \"prepare\" replaces one, "
                                 "so exactly one, or the study's \"cloud\", must name it",
                                 animated.size()));
  spec.cloud_index = animated.front();
  spec.cloud = (*clouds)[spec.cloud_index].value("name", "");
}

bool scene_json_has_target(const nlohmann::json& scene) {
  if (!scene.contains("surfaces") || !scene["surfaces"].is_array()) return false;
  for (const nlohmann::json& s : scene["surfaces"])
    if (s.is_object() && s.value("target", false) == true) return true;
  return false;
}

std::filesystem::path relative_to(const std::filesystem::path& file, const std::string& name) {
  std::filesystem::path p = name;
  return p.is_relative() ? file.parent_path() / p : p;
}

}  // namespace

StudySpec load_study(const std::filesystem::path& file) {
  return parse_study(read_json_file(file.string()), file);
}

StudySpec parse_study(const nlohmann::json& doc, const std::filesystem::path& file) {
  const std::string name = file.string();
  JsonObject root(doc, name, "");
  StudySpec spec;
  spec.file = file;
  root.string_or("description", "");
  spec.scene_path = relative_to(file, root.string("scene"));
  spec.scene = read_json_file(spec.scene_path.string());
  if (!spec.scene.is_object())
    throw InputError(spec.scene_path.string(), "", "a scene is a JSON object");
  if (root.has("prepare")) {
    spec.prepare_path = relative_to(file, root.string("prepare"));
    spec.prepare = read_json_file(spec.prepare_path.string());
    if (!spec.prepare.is_object())
      throw InputError(spec.prepare_path.string(), "", "a preparation is a JSON object");
    find_cloud(root, spec);
  }
  if (!scene_json_has_target(spec.scene))
    throw InputError(spec.scene_path.string(), "/surfaces",
                     "no surface is a target (\"target\": true): a study measures how a target "
                     "is screened");
  spec.times_s = read_times(root);
  const std::string combine = root.string_or("combine", "grid");
  if (combine != "grid" && combine != "zip")
    throw root.error("combine", "'" + combine + "' is not one of grid, zip");
  spec.zip = combine == "zip";
  spec.keep_clouds = root.boolean_or("keep_clouds", false);

  const nlohmann::json& axes = root.array("axes");
  if (axes.empty()) throw root.error("axes", "must list at least one axis");
  for (std::size_t i = 0; i < axes.size(); ++i) {
    StudyAxis axis = read_axis(axes[i], name, root.path_of("axes") + "/" + std::to_string(i), spec);
    for (const StudyAxis& other : spec.axes)
      if (other.name == axis.name)
        throw InputError(name, root.path_of("axes") + "/" + std::to_string(i) + "/name",
                         "'" + axis.name + "' names two axes");
    spec.axes.push_back(std::move(axis));
  }
  root.finish();

  if (spec.zip) {
    spec.case_count = spec.axes.front().values.size();
    for (std::size_t i = 0; i < spec.axes.size(); ++i)
      if (spec.axes[i].values.size() != spec.case_count)
        throw InputError(name, "/axes/" + std::to_string(i) + "/values",
                         fmt::format("has {} values where \"combine\": \"zip\" needs {}, as the "
                                     "first axis",
                                     spec.axes[i].values.size(), spec.case_count));
  } else {
    spec.case_count = 1;
    for (const StudyAxis& a : spec.axes) {
      if (spec.case_count > kMaxCases / a.values.size())
        throw root.error("axes", fmt::format("give more than {} cases", kMaxCases));
      spec.case_count *= a.values.size();
    }
  }
  return spec;
}

StudyCase study_case(const StudySpec& spec, std::size_t index) {
  StudyCase c;
  c.index = index;
  c.id = fmt::format("case_{:04d}", index);
  c.value.resize(spec.axes.size());
  std::size_t rest = index;
  for (std::size_t a = spec.axes.size(); a-- > 0;) {
    const std::size_t n = spec.axes[a].values.size();
    c.value[a] = spec.zip ? index : rest % n;
    rest /= n;
  }
  return c;
}

std::string describe_case(const StudySpec& spec, const StudyCase& c) {
  std::string text;
  for (std::size_t a = 0; a < spec.axes.size(); ++a) {
    const nlohmann::json& label = spec.axes[a].labels[c.value[a]];
    text += fmt::format("{}{}={}", a ? ", " : "", spec.axes[a].name,
                        label.is_string() ? label.get<std::string>() : label.dump());
  }
  return text;
}

CaseDocuments case_documents(const StudySpec& spec, const StudyCase& c,
                             const std::filesystem::path& cloud_manifest) {
  CaseDocuments d{spec.prepare, spec.scene, {}};
  for (std::size_t a = 0; a < spec.axes.size(); ++a) {
    const StudyAxis& axis = spec.axes[a];
    nlohmann::json& doc = axis.file == StudyAxis::File::kPrepare ? d.prepare : d.scene;
    doc[nlohmann::json::json_pointer(axis.path)] = axis.values[c.value[a]];
  }
  if (!spec.prepare_path.empty())
    d.scene["clouds"][spec.cloud_index]["manifest"] =
        std::filesystem::absolute(cloud_manifest).string();
  std::string times;
  for (double t : spec.times_s) times += fmt::format("{},", t);
  d.fingerprint = sha256_bytes(d.prepare.dump() + "\n" + d.scene.dump() + "\n" + times);
  return d;
}

}  // namespace obscura
