// The checked JSON parse (io/json_document.h): the document nlohmann builds,
// plus errors for duplicate keys, deep nesting and numbers out of range,
// each naming the file and the JSON path.
#include "obscura/io/json_document.h"

#include <gtest/gtest.h>

#include <string>

#include "support/input_error.h"

namespace obscura {
namespace {

using testing::contains;
using testing::expect_input_error;

InputError parse_error(const std::string& text) {
  return expect_input_error([&] { parse_json_document(text, "scene.json"); });
}

TEST(JsonDocument, BuildsTheSameDocumentAsNlohmann) {
  const std::string text = R"({"a": [1, -2, 3.5, "x", null, true, {"b": []}], "c": {"d": {}},
                               "e": 18446744073709551615, "f": [[[]]]})";
  EXPECT_EQ(parse_json_document(text, "f.json"), nlohmann::json::parse(text));
  EXPECT_EQ(parse_json_document("7", "f.json"), nlohmann::json(7));
}

TEST(JsonDocument, DuplicateKeyIsAnErrorNamingItsPath) {
  const InputError e = parse_error(R"({"sensors": [{"width": 3, "fov_deg": 1, "width": 4}]})");
  EXPECT_EQ(e.file(), "scene.json");
  EXPECT_EQ(e.field(), "/sensors/0/width");
  EXPECT_TRUE(contains(e.detail(), "duplicate key")) << e.what();
  EXPECT_EQ(parse_error(R"({"a": 1, "a": 1})").field(), "/a");
  // The same key in different objects is fine.
  EXPECT_NO_THROW(parse_json_document(R"({"a": {"a": 1}, "b": {"a": 2}})", "f.json"));
}

TEST(JsonDocument, NumberOutsideTheDoubleRangeIsNamedByField) {
  const InputError e = parse_error(R"({"clouds": [{"sigma_a": [0.1, 1e999]}]})");
  EXPECT_EQ(e.field(), "/clouds/0/sigma_a/1");
  EXPECT_TRUE(contains(e.detail(), "1e999")) << e.what();
  EXPECT_TRUE(contains(e.detail(), "outside the range of a double")) << e.what();
  EXPECT_EQ(parse_error(R"({"k": -1e400})").field(), "/k");
}

TEST(JsonDocument, DeepNestingIsAnErrorNotACrash) {
  // 100 000 levels overflowed the stack when the DOM was copied.
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  const InputError e = parse_error(deep);
  EXPECT_TRUE(contains(e.detail(), "nested more than 256 levels")) << e.what();
  EXPECT_LT(e.field().size(), 90u) << "the path is shortened";
  const std::string objects = [] {
    std::string s;
    for (int i = 0; i < 300; ++i) s += "{\"k\":";
    return s + "1" + std::string(300, '}');
  }();
  EXPECT_TRUE(contains(parse_error(objects).field(), "/k/k/k"));
  // 256 levels are accepted.
  const std::string ok = std::string(256, '[') + std::string(256, ']');
  EXPECT_NO_THROW(parse_json_document(ok, "f.json"));
}

TEST(JsonDocument, SyntaxErrorsNameLineAndColumn) {
  const InputError e = parse_error("{\n  \"a\": 1,\n  \"b\" 2\n}");
  EXPECT_EQ(e.field(), "line 3 column 7");
  EXPECT_TRUE(contains(e.detail(), "invalid JSON")) << e.what();
  EXPECT_TRUE(contains(parse_error("").detail(), "invalid JSON"));
  EXPECT_TRUE(contains(parse_error("{} x").detail(), "invalid JSON"));
}

}  // namespace
}  // namespace obscura
