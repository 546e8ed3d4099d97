#pragma once
// A parameter study (`obscura study`, docs/studies.md): a base preparation
// configuration and scene, and axes that each set one value in one of them
// (a JSON pointer) to each of a list of values: wind direction and speed,
// stability class, the devices, the material, the sensor's position or bands,
// anything either file holds. The cases are every combination of the axes'
// values ("grid", the last axis fastest) or their values taken side by side
// ("zip"). Each case is a pair of documents, prepared, rendered and measured
// by study/study_runner.h.
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace obscura {

struct StudyAxis {
  enum class File { kPrepare, kScene };
  std::string name;  // a column of the results: letters, digits, '_'
  File file = File::kPrepare;
  std::string path;  // JSON pointer into that file, e.g. "/dispersion/wind/from_deg"
  std::vector<nlohmann::json> values;
  // What the results record for each value: "labels" when given, else the
  // value itself when it is a number or a string, else its JSON text.
  std::vector<nlohmann::json> labels;
};

struct StudySpec {
  std::filesystem::path file;          // the study file
  std::filesystem::path prepare_path;  // empty when the study prepares nothing
  std::filesystem::path scene_path;
  nlohmann::json prepare, scene;  // the base documents
  // The scene's animated cloud that each case's prepared cloud replaces
  // (its index in the scene's "clouds"); unused without a preparation.
  std::string cloud;
  std::size_t cloud_index = 0;
  std::vector<double> times_s;  // the frames of every case
  bool zip = false;
  bool keep_clouds = false;  // keep each case's prepared keyframes
  std::vector<StudyAxis> axes;
  std::size_t case_count = 0;
};

// Reads and checks a study file and the base files it names (relative to its
// folder). Throws InputError naming the file and JSON path: an unknown key,
// an axis on a file the study has not got or on a value that file does not
// hold, an empty list of values, axes of different lengths with "zip", more
// than 100 000 cases, a scene without a target or without the cloud.
StudySpec load_study(const std::filesystem::path& file);
// The same from an already-parsed study document: `file` names it in errors
// and its folder is the base of the files it names.
StudySpec parse_study(const nlohmann::json& doc, const std::filesystem::path& file);

struct StudyCase {
  std::size_t index = 0;
  std::string id;                  // "case_0007"
  std::vector<std::size_t> value;  // per axis, the index of its value
};

StudyCase study_case(const StudySpec& spec, std::size_t index);

// "wind_from_deg=270, stability=D", for progress lines and errors.
std::string describe_case(const StudySpec& spec, const StudyCase& c);

// A case's documents: the base ones with the case's values set, and the
// scene's cloud pointing at `cloud_manifest` (when the study prepares one).
// `fingerprint` (SHA-256 of both and the times) tells a resumed study whether
// a stored result is this case's.
struct CaseDocuments {
  nlohmann::json prepare, scene;
  std::string fingerprint;
};
CaseDocuments case_documents(const StudySpec& spec, const StudyCase& c,
                             const std::filesystem::path& cloud_manifest);

}  // namespace obscura
