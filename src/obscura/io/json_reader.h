#pragma once
// Typed access to a JSON object that names the file and the JSON path
// ("/sensors/0/fov_deg") in every error, and reports keys nobody asked for as
// errors, so a typo in a scene is never silently ignored (pbrt-v4 ReportUnused).
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "obscura/core/error.h"
#include "obscura/core/vec3.h"

namespace obscura {

// Parses a JSON file; syntax errors name the file, line and column.
nlohmann::json read_json_file(const std::string& path);

class JsonObject {
 public:
  // Throws InputError unless `value` is an object.
  JsonObject(const nlohmann::json& value, std::string file, std::string path);

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  std::string path_of(const std::string& key) const { return path_ + "/" + key; }
  bool has(const std::string& key) const;
  InputError error(const std::string& key, const std::string& what) const {
    return InputError(file_, path_of(key), what);
  }

  // Finite numbers. The *_or forms return `fallback` when the key is absent.
  double number(const std::string& key);
  double number_or(const std::string& key, double fallback);
  std::optional<double> optional_number(const std::string& key);
  // Numbers constrained to a range, with the range in the error message.
  double positive(const std::string& key);
  double positive_or(const std::string& key, double fallback);
  long long integer(const std::string& key);
  long long integer_or(const std::string& key, long long fallback);
  std::string string(const std::string& key);
  std::string string_or(const std::string& key, const std::string& fallback);
  bool boolean_or(const std::string& key, bool fallback);
  Vec3 vec3(const std::string& key);
  Vec3 vec3_or(const std::string& key, const Vec3& fallback);
  std::vector<double> numbers(const std::string& key);
  JsonObject object(const std::string& key);
  std::optional<JsonObject> optional_object(const std::string& key);
  // An array; element i of it has the path path_of(key) + "/" + i.
  const nlohmann::json& array(const std::string& key);
  const nlohmann::json& raw(const std::string& key);

  // Throws naming the first key that was never read.
  void finish() const;

 private:
  const nlohmann::json& get(const std::string& key);
  const nlohmann::json* value_;
  std::string file_;
  std::string path_;
  std::set<std::string> used_;
  mutable std::set<std::string> known_;  // every key asked for, present or not
};

}  // namespace obscura
