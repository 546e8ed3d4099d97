#include "obscura/io/json_reader.h"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "obscura/io/input_file.h"
#include "obscura/io/json_document.h"

namespace obscura {

nlohmann::json read_json_file(const std::string& path) {
  require_regular_file(path, "JSON");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", fmt::format("cannot read file: {}", std::strerror(errno)));
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_json_document(buffer.str(), path);
}

namespace {
const char* type_name(const nlohmann::json& v) { return v.type_name(); }
}  // namespace

JsonObject::JsonObject(const nlohmann::json& value, std::string file, std::string path)
    : value_(&value), file_(std::move(file)), path_(std::move(path)) {
  if (!value.is_object())
    throw InputError(file_, path_.empty() ? "/" : path_,
                     fmt::format("expected a JSON object, found {}", type_name(value)));
}

bool JsonObject::has(const std::string& key) const {
  known_.insert(key);
  return value_->contains(key);
}

const nlohmann::json& JsonObject::get(const std::string& key) {
  known_.insert(key);
  auto it = value_->find(key);
  if (it == value_->end()) throw error(key, "missing required field");
  used_.insert(key);
  return *it;
}

const nlohmann::json& JsonObject::raw(const std::string& key) { return get(key); }

double JsonObject::number(const std::string& key) {
  const auto& v = get(key);
  if (!v.is_number()) throw error(key, fmt::format("expected a number, found {}", type_name(v)));
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw error(key, "expected a finite number");
  return x;
}

double JsonObject::number_or(const std::string& key, double fallback) {
  return has(key) ? number(key) : fallback;
}

std::optional<double> JsonObject::optional_number(const std::string& key) {
  if (!has(key)) return std::nullopt;
  return number(key);
}

double JsonObject::positive(const std::string& key) {
  const double x = number(key);
  if (!(x > 0)) throw error(key, fmt::format("expected a number > 0, found {}", x));
  return x;
}

double JsonObject::positive_or(const std::string& key, double fallback) {
  return has(key) ? positive(key) : fallback;
}

long long JsonObject::integer(const std::string& key) {
  const auto& v = get(key);
  if (!v.is_number_integer())
    throw error(key, fmt::format("expected an integer, found {}", v.dump()));
  // Above 2^63 - 1 nlohmann keeps an unsigned value, which get<long long> would wrap.
  if (v.is_number_unsigned() &&
      v.get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<long long>::max()))
    throw error(key, fmt::format("integer {} is out of range", v.dump()));
  return v.get<long long>();
}

long long JsonObject::integer_or(const std::string& key, long long fallback) {
  return has(key) ? integer(key) : fallback;
}

std::string JsonObject::string(const std::string& key) {
  const auto& v = get(key);
  if (!v.is_string()) throw error(key, fmt::format("expected a string, found {}", type_name(v)));
  return v.get<std::string>();
}

std::string JsonObject::string_or(const std::string& key, const std::string& fallback) {
  return has(key) ? string(key) : fallback;
}

bool JsonObject::boolean_or(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  const auto& v = get(key);
  if (!v.is_boolean())
    throw error(key, fmt::format("expected true or false, found {}", type_name(v)));
  return v.get<bool>();
}

std::vector<double> JsonObject::numbers(const std::string& key) {
  const auto& v = get(key);
  if (!v.is_array())
    throw error(key, fmt::format("expected an array of numbers, found {}", type_name(v)));
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_number())
      throw InputError(file_, fmt::format("{}/{}", path_of(key), i),
                       fmt::format("expected a number, found {}", type_name(v[i])));
    const double x = v[i].get<double>();
    if (!std::isfinite(x))
      throw InputError(file_, fmt::format("{}/{}", path_of(key), i), "expected a finite number");
    out.push_back(x);
  }
  return out;
}

Vec3 JsonObject::vec3(const std::string& key) {
  const auto values = numbers(key);
  if (values.size() != 3)
    throw error(key, fmt::format("expected 3 numbers [x, y, z], found {}", values.size()));
  return {values[0], values[1], values[2]};
}

Vec3 JsonObject::vec3_or(const std::string& key, const Vec3& fallback) {
  return has(key) ? vec3(key) : fallback;
}

JsonObject JsonObject::object(const std::string& key) {
  return JsonObject(get(key), file_, path_of(key));
}

std::optional<JsonObject> JsonObject::optional_object(const std::string& key) {
  if (!has(key)) return std::nullopt;
  return object(key);
}

const nlohmann::json& JsonObject::array(const std::string& key) {
  const auto& v = get(key);
  if (!v.is_array()) throw error(key, fmt::format("expected an array, found {}", type_name(v)));
  return v;
}

void JsonObject::finish() const {
  for (auto it = value_->begin(); it != value_->end(); ++it) {
    if (!used_.count(it.key())) {
      std::string known;
      for (const auto& k : known_) known += (known.empty() ? "" : ", ") + k;
      throw InputError(
          file_, path_of(it.key()),
          fmt::format("unknown field (expected one of: {})", known.empty() ? "none" : known));
    }
  }
}

}  // namespace obscura
