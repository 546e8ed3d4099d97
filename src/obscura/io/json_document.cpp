#include "obscura/io/json_document.h"

#include <fmt/format.h>

#include <optional>
#include <vector>

#include "obscura/core/error.h"

namespace obscura {
namespace {

using json = nlohmann::json;

// The line and column of byte `offset` of `text`, for syntax errors.
std::string line_and_column(const std::string& text, std::size_t offset) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i + 1 < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return fmt::format("line {} column {}", line, column);
}

// Builds the document as nlohmann's DOM parser does (the parse itself is
// iterative, so depth costs no stack here), checking as it goes.
class CheckedBuilder : public nlohmann::json_sax<json> {
 public:
  CheckedBuilder(const std::string& text, const std::string& file) : text_(text), file_(file) {}

  json take() { return std::move(root_); }

  bool null() override { return put(json(nullptr)); }
  bool boolean(bool v) override { return put(json(v)); }
  bool number_integer(number_integer_t v) override { return put(json(v)); }
  bool number_unsigned(number_unsigned_t v) override { return put(json(v)); }
  bool number_float(number_float_t v, const string_t&) override { return put(json(v)); }
  bool string(string_t& v) override { return put(json(std::move(v))); }
  bool binary(binary_t& v) override { return put(json::binary(std::move(v))); }

  bool start_object(std::size_t) override { return open(json::object()); }
  bool start_array(std::size_t) override { return open(json::array()); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }

  bool key(string_t& k) override {
    if (stack_.back()->contains(k))
      throw InputError(file_, shorten(path() + "/" + k),
                       "duplicate key: a key may appear only once in an object");
    key_ = std::move(k);
    return true;
  }

  bool parse_error(std::size_t position, const std::string& token,
                   const nlohmann::detail::exception& e) override {
    // 406: a number the lexer read but a double cannot hold (1e999).
    if (e.id == 406)
      throw InputError(
          file_, shorten(next_path()),
          fmt::format("number {} is outside the range of a double (about ±1.8e308)", token));
    std::string what = e.what();
    const auto at = what.find("syntax error");
    throw InputError(file_, line_and_column(text_, position),
                     "invalid JSON: " + (at == std::string::npos ? what : what.substr(at)));
  }

 private:
  // The JSON path of the container being filled ("" at the top).
  std::string path() const {
    std::string p;
    for (const auto& s : segments_) p += "/" + s;
    return p;
  }
  // The JSON path the next value will have.
  std::string next_path() const {
    if (stack_.empty()) return "/";
    const json& top = *stack_.back();
    return path() + "/" + (top.is_object() ? key_ : std::to_string(top.size()));
  }
  // A path 256 levels deep is 512 characters of "/0": keep the start.
  static std::string shorten(const std::string& p) {
    return p.size() <= 80 ? p : p.substr(0, 60) + "/…";
  }

  // Places `v` where the next value goes and returns a pointer to it there.
  json* place(json&& v) {
    if (stack_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    json& top = *stack_.back();
    if (top.is_object()) return &(top[key_] = std::move(v));
    top.push_back(std::move(v));
    return &top.back();
  }
  bool put(json&& v) {
    place(std::move(v));
    return true;
  }
  bool open(json&& container) {
    if (stack_.size() >= kMaxJsonDepth)
      throw InputError(
          file_, shorten(next_path()),
          fmt::format("arrays and objects nested more than {} levels deep", kMaxJsonDepth));
    std::string segment;
    if (!stack_.empty())
      segment = stack_.back()->is_object() ? key_ : std::to_string(stack_.back()->size());
    // Pointers to the open containers stay valid: only the innermost one
    // grows, and nothing points into it until it is closed.
    json* slot = place(std::move(container));
    if (!stack_.empty()) segments_.push_back(std::move(segment));
    stack_.push_back(slot);
    return true;
  }
  bool close() {
    stack_.pop_back();
    if (!segments_.empty() && stack_.size() == segments_.size()) segments_.pop_back();
    return true;
  }

  const std::string& text_;
  const std::string& file_;
  json root_;
  std::vector<json*> stack_;
  std::vector<std::string> segments_;  // path of stack_.back() below the root
  std::string key_;
};

}  // namespace

nlohmann::json parse_json_document(const std::string& text, const std::string& file) {
  CheckedBuilder builder(text, file);
  json::sax_parse(text, &builder);
  return builder.take();
}

}  // namespace obscura
