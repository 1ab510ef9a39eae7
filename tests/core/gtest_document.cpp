#include "rondo/core/document.h"

#include <gtest/gtest.h>

namespace rondo {
namespace {

Document yaml(std::string_view text) {
  auto doc = Document::parse(text, DocumentFormat::kYaml, "t.yaml");
  EXPECT_TRUE(doc.ok()) << (doc.ok() ? "" : doc.error().message);
  return *doc;
}

TEST(Document, TypesYamlScalarsByTheCoreSchema) {
  const Document doc = yaml("a: 12\nb: 1.5\nc: true\nd: ~\ne: '12'\nf: 1h30m\ng: \"true\"\nh: 08:45\ni: -3\n");
  const Json& j = doc.json();
  EXPECT_EQ(j["a"], 12);
  EXPECT_EQ(j["b"], 1.5);
  EXPECT_EQ(j["c"], true);
  EXPECT_TRUE(j["d"].is_null());
  EXPECT_EQ(j["e"], "12");
  EXPECT_EQ(j["f"], "1h30m");
  EXPECT_EQ(j["g"], "true");
  EXPECT_EQ(j["h"], "08:45");
  EXPECT_EQ(j["i"], -3);
}

TEST(Document, ErrorsNameFileLineAndPath) {
  const Document doc = yaml("tasks:\n  - id: a\n    priority: high\n");
  auto items = doc.root().required("tasks")->items();
  ASSERT_TRUE(items.ok());
  auto p = (*items)[0].required("priority")->as_int();
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error().message, "t.yaml:3: tasks[0].priority: expected an integer, found text");
  auto missing = (*items)[0].required("window");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().message, "t.yaml:2: tasks[0]: missing field 'window'");
}

TEST(Document, UnknownKeysAreNamed) {
  const Document doc = yaml("id: a\nwindwo: {}\n");
  auto s = doc.root().expect_keys({"id", "window"});
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("t.yaml:2: windwo: unknown field 'windwo'"), std::string::npos) << s.error().message;
}

TEST(Document, MalformedTextIsAnErrorNotACrash) {
  struct Case {
    DocumentFormat format;
    std::string text;
    std::string expect;  // part of the message
  };
  const Case cases[] = {
      {DocumentFormat::kYaml, "a: [1, 2", "t:"},
      {DocumentFormat::kYaml, "a: 1\na: 2\n", "duplicate key 'a'"},
      {DocumentFormat::kYaml, "a:\n  - b\n c: d\n", "t:"},
      {DocumentFormat::kYaml, std::string(200, '[') + std::string(200, ']'), "nested deeper than"},
      {DocumentFormat::kJson, "{\"a\": 1,", "t: "},
      {DocumentFormat::kJson, std::string(100000, '['), "nested deeper than"},
      {DocumentFormat::kJson, std::string(65, '[') + std::string(65, ']'), "nested deeper than 64 levels"},
      {DocumentFormat::kYaml, std::string(65, '[') + std::string(65, ']'), "nested deeper than 64 levels"},
      {DocumentFormat::kYaml, "? [a, b]\n: c\n", "keys must be plain text"},
      {DocumentFormat::kYaml, "a: b\nc: \xff\xfe\n", "t:2: the text is not valid UTF-8"},
      {DocumentFormat::kYaml, "a: \xed\xa0\x80\n", "t:1: the text is not valid UTF-8"},  // a lone surrogate
      {DocumentFormat::kJson, "{\"a\": \"\xc3\"}", "t:1: the text is not valid UTF-8"},
  };
  for (const auto& c : cases) {
    auto doc = Document::parse(c.text, c.format, "t");
    ASSERT_FALSE(doc.ok()) << c.text.substr(0, 40);
    EXPECT_EQ(doc.error().code, ErrorCode::kInvalidInput);
    EXPECT_NE(doc.error().message.find(c.expect), std::string::npos) << doc.error().message;
  }
}

TEST(Document, SixtyFourLevelsAreAllowed) {
  for (auto format : {DocumentFormat::kYaml, DocumentFormat::kJson}) {
    auto doc = Document::parse(std::string(64, '[') + std::string(64, ']'), format, "t");
    EXPECT_TRUE(doc.ok()) << doc.error().message;
  }
}

TEST(Document, BracketsInsideTextDoNotCountAsNesting) {
  std::string text = "names:\n";
  for (int i = 0; i < 300; ++i) text += "  - Room [" + std::to_string(i) + "\n";
  text += "quoted: \"[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[\"\n";
  auto doc = Document::parse(text, DocumentFormat::kYaml, "t.yaml");
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  EXPECT_EQ(doc->json()["names"][299], "Room [299");
}

TEST(Document, DeepBlockNestingIsRejected) {
  std::string text;
  for (int i = 0; i < 100; ++i) text += std::string(static_cast<std::size_t>(i), ' ') + "k:\n";
  auto doc = Document::parse(text, DocumentFormat::kYaml, "deep.yaml");
  ASSERT_FALSE(doc.ok());
  EXPECT_NE(doc.error().message.find("nested deeper than"), std::string::npos);
}

TEST(Document, LoadNamesAMissingFile) {
  auto doc = Document::load("no/such/file.yaml");
  ASSERT_FALSE(doc.ok());
  EXPECT_EQ(doc.error().code, ErrorCode::kNotFound);
  EXPECT_NE(doc.error().message.find("no/such/file.yaml"), std::string::npos);
}

TEST(Document, YamlWriterQuotesWhatWouldChangeType) {
  const Json j{{"a", "12"}, {"b", 12}, {"c", "true"}, {"d", "plain text"}, {"e", 0.1}, {"f", ""}};
  auto back = Document::parse(to_yaml(j), DocumentFormat::kYaml, "w");
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->json(), j);
}

}  // namespace
}  // namespace rondo
