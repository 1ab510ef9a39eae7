#include "rondo/core/document.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/alias_bomb.h"
#include "rondo/core/utf8.h"
#include "test_files.h"

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

// nlohmann keeps the last of a key given twice without a word, and a YAML mapping with a duplicate
// key is refused: a JSON object is refused the same way, naming the line of the second key and its
// path. The same key in two objects is not a duplicate.
TEST(Document, JsonRefusesADuplicateKeyNamingItsLineAndPath) {
  struct Case {
    std::string text;
    std::string expect;  // the whole message; empty: the text is accepted
  };
  const Case cases[] = {
      {R"({"a": 1, "a": 2})", "t.json:1: a: duplicate key 'a'"},
      {"{\n  \"tasks\": [\n    {\"id\": \"x\",\n     \"id\": \"y\"}\n  ]\n}\n",
       "t.json:4: tasks[0].id: duplicate key 'id'"},
      {"{\"l\": [1, [2], {\"k\": 1,\n\n \"k\": 2}]}", "t.json:3: l[2].k: duplicate key 'k'"},
      {R"({"a": {"b": {"c": 1}}, "a": 2})", "t.json:1: a: duplicate key 'a'"},
      {R"({"a": 1, "\u0061": 2})", "t.json:1: a: duplicate key 'a'"},  // the same key once unescaped
      {R"({"a": {"x": 1}, "b": {"x": 2}, "c": [{"x": 1}, {"x": 2}]})", ""},
      {R"({"a": 1, "A": 2, "a ": 3})", ""},
  };
  for (const auto& c : cases) {
    auto doc = Document::parse(c.text, DocumentFormat::kJson, "t.json");
    if (c.expect.empty()) {
      EXPECT_TRUE(doc.ok()) << c.text << ": " << doc.error().message;
      continue;
    }
    ASSERT_FALSE(doc.ok()) << c.text;
    EXPECT_EQ(doc.error().code, ErrorCode::kInvalidInput);
    EXPECT_EQ(doc.error().message, c.expect) << c.text;
  }
  // Through a file, as every JSON loader reads it: the message names the file.
  const auto file = test::fresh_dir("rondo-document-test", "duplicate") / "day.json";
  std::ofstream(file) << "{\"tasks\": [],\n \"tasks\": []}\n";
  auto loaded = Document::load(file);
  ASSERT_FALSE(loaded.ok());
  EXPECT_EQ(loaded.error().message, file.string() + ":2: tasks: duplicate key 'tasks'");
}

// Found by fuzz_problem and fuzz_models: the parsers' own messages quote the byte they stopped at,
// which can be the first byte of a longer UTF-8 character; the message must still be text.
TEST(Document, ParserMessagesAreValidUtf8) {
  struct Case {
    DocumentFormat format;
    std::string text;
  };
  const Case cases[] = {
      {DocumentFormat::kYaml, "a: \"\\\xc3\xa9\"\n"},       // an escape of a two-byte character
      {DocumentFormat::kJson, "[17\xc3\xa9]"},              // an invalid literal ending in one
      {DocumentFormat::kJson, "{\"a\": tru\xe2\x82\xac}"},  // a three-byte one
      {DocumentFormat::kYaml, std::string("\x00 #n\x00r\r@b\x00\x00"
                                          "e #n\x00r\r@b\x00\x00"
                                          "etraveltravel[0][1]",
                                          42)},
  };
  for (const auto& c : cases) {
    auto doc = Document::parse(c.text, c.format, "t");
    if (doc.ok()) continue;
    EXPECT_EQ(doc.error().code, ErrorCode::kInvalidInput);
    EXPECT_FALSE(first_invalid_utf8(doc.error().message).has_value()) << replace_invalid_utf8(doc.error().message);
  }
}

// Found by fuzz_world and fuzz_requests: yaml-cpp turns some bytes of valid UTF-8 text (a NUL
// inside a plain key) into a string that is not UTF-8; such a scalar is refused, not passed on.
TEST(Document, EveryScalarThatComesBackIsUtf8) {
  using namespace std::string_literals;  // the literals' own lengths, NULs included
  const std::string cases[] = {
      "wilogs      \x00_hour: 5.52\n\0"s,  // the fuzzers' inputs end in a NUL
      "id\x07\x00_prefix: &eq\nday: 1\n\0"s,
      "a: \"x\x00y\"\n\0"s,
      "# Tml: every edgebattery.ompt s6t\000@`\000\000.\012kind: replay\012logs: ../. "
      "0.01\032\032\032\032\032\032\032h\032\032\032\032\032\032\032 ../. "
      "0.01\032\032\032\032\032\032\032h\032\032\032\032\032\032\032so Europe/London\012wilogs      "
      "\000_hour: 5.52}\012"s,
      "#office asking the robot for thi\012id\007\000_prefix: &eq\012day# Peopleffi2r t,h"s,
  };
  for (const auto& text : cases) {
    auto doc = Document::parse(text, DocumentFormat::kYaml, "t.yaml");
    if (!doc.ok()) {
      EXPECT_FALSE(first_invalid_utf8(doc.error().message).has_value()) << replace_invalid_utf8(doc.error().message);
      continue;
    }
    const std::string dumped = doc->json().dump(-1, ' ', false, Json::error_handler_t::replace);
    EXPECT_EQ(dumped.find("\xef\xbf\xbd"), std::string::npos) << dumped;  // nothing needed replacing
    for (const auto& [key, value] : doc->json().items()) EXPECT_FALSE(first_invalid_utf8(key).has_value());
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

TEST(Document, AnAliasBombIsRefusedByCountingValues) {
  const std::string bomb = test::alias_bomb();
  ASSERT_LT(bomb.size(), 1024u);
  auto doc = Document::parse(bomb, DocumentFormat::kYaml, "bomb.yaml");
  ASSERT_FALSE(doc.ok());
  EXPECT_EQ(doc.error().code, ErrorCode::kInvalidInput);
  EXPECT_NE(doc.error().message.find("bomb.yaml:"), std::string::npos) << doc.error().message;
  EXPECT_NE(doc.error().message.find(test::kAliasBombLimit), std::string::npos) << doc.error().message;
}

TEST(Document, LimitsOnAliasesAreCountedAndNamed) {
  struct Case {
    std::string name;
    std::string text;
    std::string expect;
  };
  std::string many_aliases = "a: &a x\nl:\n";
  for (std::size_t i = 0; i <= Document::kMaxAliases; ++i) many_aliases += "- *a\n";
  std::string deep_aliases = "a0: &a0 [x]\n";
  for (int i = 1; i <= Document::kMaxAliasDepth + 1; ++i) {
    deep_aliases += "a" + std::to_string(i) + ": &a" + std::to_string(i) + " [*a" + std::to_string(i - 1) + "]\n";
  }
  std::string deep_by_alias = "a: &a " + std::string(40, '[') + std::string(40, ']') + "\nb: " + std::string(30, '[') +
                              "*a" + std::string(30, ']') + "\n";
  const Case cases[] = {
      {"aliases", many_aliases, "more than 100000 aliases (the limit is 100000)"},
      {"alias depth", deep_aliases, "aliases nest more than 16 deep (the limit is 16)"},
      {"depth through an alias", deep_by_alias, "nested deeper than 64 levels"},
      {"recursive alias", "a: &a [1, *a]\n", "an alias refers to a collection that contains it"},
      {"too big", std::string(Document::kMaxBytes + 1, '#'), "more than the limit of 16777216 bytes"},
  };
  for (const auto& c : cases) {
    auto doc = Document::parse(c.text, DocumentFormat::kYaml, "t.yaml");
    ASSERT_FALSE(doc.ok()) << c.name;
    EXPECT_EQ(doc.error().code, ErrorCode::kInvalidInput) << c.name;
    EXPECT_NE(doc.error().message.find(c.expect), std::string::npos) << c.name << ": " << doc.error().message;
  }
}

TEST(Document, JsonCountsValuesToo) {
  std::string text = "[";
  for (std::size_t i = 0; i <= Document::kMaxValues; ++i) text += i ? ",0" : "0";
  text += "]";
  auto doc = Document::parse(text, DocumentFormat::kJson, "t.json");
  ASSERT_FALSE(doc.ok());
  EXPECT_NE(doc.error().message.find("more than 2000000 values"), std::string::npos) << doc.error().message;
}

TEST(Document, OrdinaryAnchorsAndAliasesStillWork) {
  const Document doc = yaml(
      "meta: &meta {map: riseholme, pointset: x}\n"
      "quoted: &q '12'\n"
      "nodes:\n"
      "  - {name: A, meta: *meta, n: *q}\n"
      "  - name: B\n"
      "    meta: *meta\n"
      "    edges: &edges [{to: A}, {to: C}]\n"
      "  - {name: C, edges: *edges}\n"
      "&k key: 1\n"
      "other: {*k : 2}\n");
  const Json& j = doc.json();
  EXPECT_EQ(j["nodes"][0]["meta"]["map"], "riseholme");
  EXPECT_EQ(j["nodes"][0]["n"], "12");
  EXPECT_EQ(j["nodes"][1]["meta"], j["meta"]);
  EXPECT_EQ(j["nodes"][2]["edges"][1]["to"], "C");
  EXPECT_EQ(j["other"]["key"], 2);
  EXPECT_EQ(doc.line_of("nodes[1].edges"), 7);
  EXPECT_EQ(doc.line_of("nodes[2]"), 8);
}

TEST(Document, LoadRefusesAFileLargerThanTheLimitBeforeReadingIt) {
  const auto file = std::filesystem::temp_directory_path() / "rondo_document_big.yaml";
  {
    std::ofstream out(file, std::ios::binary);
    out.seekp(static_cast<std::streamoff>(Document::kMaxBytes) + 10);
    out << '\n';
  }
  auto doc = Document::load(file);
  std::filesystem::remove(file);
  ASSERT_FALSE(doc.ok());
  EXPECT_EQ(doc.error().code, ErrorCode::kInvalidInput);
  EXPECT_NE(doc.error().message.find("more than the limit of 16777216 bytes"), std::string::npos)
      << doc.error().message;
}

}  // namespace
}  // namespace rondo
