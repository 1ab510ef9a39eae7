// A parsed YAML or JSON document that remembers where each value came from, and `Field`, a read
// cursor that decoders use so that every error names the file, the line and the field path:
//
//   auto doc = Document::load("tasks.yaml");             // or Document::parse(text, kYaml, name)
//   Field root = doc->root();
//   if (auto s = root.expect_keys({"tasks", "routines"}); !s) return s.error();
//   auto tasks = root.required("tasks");                  // Result<Field>
//   for (const Field& t : *tasks->items()) {
//     Result<std::string> id = t.required("id")->as_string();   (check each Result in real code)
//   }
//   // error text: "tasks.yaml:14: tasks[2].window.deadline: must not be before the release"
//
// YAML scalars are typed the YAML 1.2 core-schema way (true/false, null/~, integers, floats);
// quoted scalars stay strings. Nesting deeper than kMaxDepth is rejected, not recursed into.
//
// Limits before work (docs/hardening.md lists them): a text longer than kMaxBytes is refused
// before it is parsed, and a tree is built value by value, counting every value an alias repeats,
// so that more than kMaxValues values, kMaxAliases aliases or aliases nested kMaxAliasDepth deep
// stop the parse with an input error that names the limit. Ordinary anchors and aliases work.
#pragma once

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "rondo/core/result.h"
#include "rondo/core/time.h"

namespace rondo {

class TimeZone;
class Field;

// Documents keep the key order of the text, so that files written back read naturally.
using Json = nlohmann::ordered_json;

enum class DocumentFormat { kYaml, kJson };

class Document {
 public:
  static constexpr int kMaxDepth = 64;                       // levels of lists and mappings
  static constexpr std::size_t kMaxBytes = 16u << 20;        // 16 MiB of text
  static constexpr std::size_t kMaxValues = 2'000'000;       // values, once aliases are expanded
  static constexpr std::size_t kMaxAliases = 100'000;        // alias uses (*name) in one document
  static constexpr int kMaxAliasDepth = 16;                  // aliases to anchors holding aliases...

  // `source` names the text in messages (usually the file path).
  static Result<Document> parse(std::string_view text, DocumentFormat format, std::string source);
  // Reads a file; ".json" is read as JSON, anything else as YAML.
  static Result<Document> load(const std::filesystem::path& file);

  Field root() const;
  const Json& json() const { return *json_; }
  const std::string& source() const { return *source_; }
  // 1-based source line of the value at `path` ("" is the root), when the format records it.
  std::optional<int> line_of(const std::string& path) const;

 private:
  Document() = default;
  // Shared so that Fields stay valid when the Document is moved.
  std::shared_ptr<Json> json_;
  std::shared_ptr<std::map<std::string, int>> lines_;
  std::shared_ptr<std::string> source_;
  friend class Field;
};

// A read-only view of one value in a Document. Cheap to copy; keeps the document alive.
class Field {
 public:
  const Json& json() const { return *value_; }
  // The path from the root, e.g. "tasks[2].window.deadline"; "" for the root itself.
  const std::string& path() const { return path_; }

  bool is_null() const { return value_->is_null(); }
  bool is_object() const { return value_->is_object(); }
  bool is_array() const { return value_->is_array(); }
  bool is_string() const { return value_->is_string(); }
  bool has(std::string_view key) const;

  // The member `key`; an error naming the missing field if this is not an object that has it.
  Result<Field> required(std::string_view key) const;
  // The member `key`, or nothing when it is absent or null.
  std::optional<Field> optional(std::string_view key) const;
  // The elements of an array; an error if this is not an array.
  Result<std::vector<Field>> items() const;
  // The members of an object, in document order for YAML (JSON objects keep key order too).
  Result<std::vector<std::pair<std::string, Field>>> members() const;

  // Checks that this is an object whose keys are all in `allowed`; names the first stranger.
  Status expect_keys(std::initializer_list<std::string_view> allowed) const;
  Status expect_keys(std::span<const std::string_view> allowed) const;

  Result<std::string> as_string() const;
  Result<double> as_number() const;  // finite numbers only
  Result<std::int64_t> as_int() const;
  Result<bool> as_bool() const;
  // A number of seconds, or a string that parse_duration() accepts.
  Result<Duration> as_duration() const;
  // An ISO 8601 string; without a zone it is read in `zone` (an error if `zone` is null).
  Result<Time> as_time(const TimeZone* zone) const;

  // Where this field is, as errors name it: "file:line: path" (no line when the format has none).
  std::string where() const;
  // An invalid-input error located at this field: "file:line: path: what".
  Error error(std::string_view what) const;
  // The same for a field below this one, named by a relative path such as "window.deadline";
  // the line is that field's when the document has it, else this one's.
  Error error_at(std::string_view relative_path, std::string_view what) const;

 private:
  friend class Document;
  Field(Document doc, const Json* value, std::string path)
      : doc_(std::move(doc)), value_(value), path_(std::move(path)) {}
  Field child(const std::string& path, const Json* value) const;
  Document doc_;  // shares the parsed tree, so the Field stays valid on its own
  const Json* value_;
  std::string path_;
};

// The YAML text of a JSON value (block style, keys in the value's order), for writers.
std::string to_yaml(const Json& value);

// Reads a whole file; kNotFound or kIo naming the file on failure, kInvalidInput past `max_bytes`.
Result<std::string> read_text_file(const std::filesystem::path& file,
                                   std::size_t max_bytes = std::size_t{1} << 30);

}  // namespace rondo
