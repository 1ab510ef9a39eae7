#include "rondo/core/document.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "rondo/core/timezone.h"
#include "rondo/core/utf8.h"
#include "json_tree.h"
#include "yaml_tree.h"

namespace rondo {
namespace {

std::string join_key(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}
std::string join_index(const std::string& parent, std::size_t i) {
  return parent + "[" + std::to_string(i) + "]";
}

// Guards yaml-cpp's recursive parser: rejects YAML whose flow collections ('[', '{') open more
// than kMaxFlowDepth levels deep before the parser sees it. A bracket counts only where YAML can
// start a collection (first on its line, or after ':', '-', '?', ',', '[' or '{'), and quoted
// scalars and comments are skipped, so text such as "Room [3" is never miscounted. This is only a
// stack guard: the exact nesting limit (Document::kMaxDepth) is enforced on the parsed tree.
constexpr int kMaxFlowDepth = 4 * Document::kMaxDepth;

Status check_yaml_flow_depth(std::string_view text, const std::string& source) {
  int depth = 0;
  int line = 1;
  char previous = '\n';  // the last character that was not a space or tab
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      previous = '\n';
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\r') continue;
    const bool at_node_start = previous == '\n' || previous == ':' || previous == '-' || previous == '?' ||
                               previous == ',' || previous == '[' || previous == '{';
    if (c == '#' && (i == 0 || text[i - 1] == ' ' || text[i - 1] == '\t' || text[i - 1] == '\n')) {
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;  // a comment runs to the end of the line
      continue;
    }
    if (at_node_start && (c == '"' || c == '\'')) {  // skip a quoted scalar
      for (++i; i < text.size(); ++i) {
        if (text[i] == '\n') ++line;
        if (c == '"' && text[i] == '\\') {
          ++i;
        } else if (text[i] == c) {
          if (c == '\'' && i + 1 < text.size() && text[i + 1] == '\'') {
            ++i;  // '' is an escaped quote
          } else {
            break;
          }
        }
      }
      previous = c;
      continue;
    }
    if (at_node_start && (c == '[' || c == '{')) {
      if (++depth > kMaxFlowDepth) {
        return Error::invalid(source + ":" + std::to_string(line) + ": nested deeper than " +
                              std::to_string(Document::kMaxDepth) + " levels");
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
    previous = c;
  }
  return {};
}

// The line of the first byte that is not part of well-formed UTF-8, if any. Text files are UTF-8;
// rejecting anything else here means no string that reaches a decoder can fail to print.
std::optional<int> first_invalid_utf8_line(std::string_view text) {
  const auto at = first_invalid_utf8(text);
  if (!at) return std::nullopt;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(*at), '\n'));
}

}  // namespace

Result<Document> Document::parse(std::string_view text, DocumentFormat format, std::string source) {
  Document doc;
  doc.source_ = std::make_shared<std::string>(std::move(source));
  doc.lines_ = std::make_shared<std::map<std::string, int>>();
  if (text.size() > kMaxBytes) {
    return Error::invalid(*doc.source_ + ": " + std::to_string(text.size()) + " bytes, more than the limit of " +
                          std::to_string(kMaxBytes) + " bytes");
  }
  if (auto line = first_invalid_utf8_line(text)) {
    return Error::invalid(*doc.source_ + ":" + std::to_string(*line) + ": the text is not valid UTF-8");
  }
  if (format == DocumentFormat::kJson) {
    auto json = detail::json_to_tree(text, *doc.source_);
    if (!json) return json.error();
    doc.json_ = std::make_shared<Json>(std::move(*json));
    return doc;
  }
  if (auto s = check_yaml_flow_depth(text, *doc.source_); !s) return s.error();
  try {
    auto json = detail::yaml_to_json(text, *doc.source_, *doc.lines_);
    if (!json) return json.error();
    doc.json_ = std::make_shared<Json>(std::move(*json));
  } catch (const YAML::Exception& e) {
    return Error::invalid(*doc.source_ + ":" + std::to_string(e.mark.line + 1) + ": " + quote_for_message(e.msg, 400));
  } catch (const std::exception& e) {
    return Error::invalid(*doc.source_ + ": " + quote_for_message(e.what(), 400));
  }
  return doc;
}

Result<std::string> read_text_file(const std::filesystem::path& file, std::size_t max_bytes) {
  const std::string name = printable_path(file);
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return Error::not_found(name + ": no such file");
  if (std::filesystem::is_directory(file, ec)) return Error::invalid(name + ": is a folder, not a file");
  const auto too_big = [&](std::uintmax_t size) {
    return Error::invalid(name + ": " + (size == 0 ? "more" : std::to_string(size)) +
                          " bytes, more than the limit of " + std::to_string(max_bytes) + " bytes");
  };
  if (const auto size = std::filesystem::file_size(file, ec); !ec && size > max_bytes) return too_big(size);
  std::ifstream in(file, std::ios::binary);
  if (!in) return Error::io(name + ": cannot open: " + std::strerror(errno));
  // Read in pieces and stop past the limit, since a pipe or a device has no size to check first.
  std::string text;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_bytes) return too_big(0);
  }
  if (in.bad()) return Error::io(name + ": read failed");
  return text;
}

Result<Document> Document::load(const std::filesystem::path& file) {
  auto text = read_text_file(file, kMaxBytes);
  if (!text) return text.error();
  const auto format = file.extension() == ".json" ? DocumentFormat::kJson : DocumentFormat::kYaml;
  return parse(*text, format, printable_path(file));
}

Field Document::root() const { return Field(*this, json_.get(), ""); }

std::optional<int> Document::line_of(const std::string& path) const {
  auto it = lines_->find(path);
  if (it == lines_->end()) return std::nullopt;
  return it->second;
}

Field Field::child(const std::string& path, const Json* value) const { return Field(doc_, value, path); }

bool Field::has(std::string_view key) const {
  return value_->is_object() && value_->contains(std::string(key));
}

Result<Field> Field::required(std::string_view key) const {
  if (!value_->is_object()) return error("expected a mapping with a field '" + std::string(key) + "'");
  auto it = value_->find(std::string(key));
  if (it == value_->end()) return error("missing field '" + std::string(key) + "'");
  return child(join_key(path_, key), &*it);
}

std::optional<Field> Field::optional(std::string_view key) const {
  if (!value_->is_object()) return std::nullopt;
  auto it = value_->find(std::string(key));
  if (it == value_->end() || it->is_null()) return std::nullopt;
  return child(join_key(path_, key), &*it);
}

Result<std::vector<Field>> Field::items() const {
  if (!value_->is_array()) return error("expected a list");
  std::vector<Field> out;
  out.reserve(value_->size());
  for (std::size_t i = 0; i < value_->size(); ++i) out.push_back(child(join_index(path_, i), &(*value_)[i]));
  return out;
}

Result<std::vector<std::pair<std::string, Field>>> Field::members() const {
  if (!value_->is_object()) return error("expected a mapping");
  std::vector<std::pair<std::string, Field>> out;
  for (auto it = value_->begin(); it != value_->end(); ++it) {
    out.emplace_back(it.key(), child(join_key(path_, it.key()), &it.value()));
  }
  return out;
}

Status Field::expect_keys(std::initializer_list<std::string_view> allowed) const {
  return expect_keys(std::span<const std::string_view>(allowed.begin(), allowed.size()));
}

Status Field::expect_keys(std::span<const std::string_view> allowed) const {
  if (!value_->is_object()) return error("expected a mapping");
  for (auto it = value_->begin(); it != value_->end(); ++it) {
    bool known = false;
    for (auto a : allowed) known = known || a == it.key();
    if (!known) {
      std::string list;
      for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      return child(join_key(path_, it.key()), &it.value())
          .error("unknown field '" + it.key() + "' (expected one of: " + list + ")");
    }
  }
  return {};
}

namespace {
const char* type_name(const Json& v) {
  switch (v.type()) {
    case Json::value_t::null: return "nothing";
    case Json::value_t::object: return "a mapping";
    case Json::value_t::array: return "a list";
    case Json::value_t::string: return "text";
    case Json::value_t::boolean: return "true/false";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned: return "an integer";
    case Json::value_t::number_float: return "a number";
    default: return "a value";
  }
}
}  // namespace

Result<std::string> Field::as_string() const {
  if (!value_->is_string()) return error(std::string("expected text, found ") + type_name(*value_));
  return value_->get<std::string>();
}

Result<double> Field::as_number() const {
  if (!value_->is_number()) return error(std::string("expected a number, found ") + type_name(*value_));
  const double v = value_->get<double>();
  if (!std::isfinite(v)) return error("expected a finite number");
  return v;
}

Result<std::int64_t> Field::as_int() const {
  if (value_->is_number_integer()) return value_->get<std::int64_t>();
  if (value_->is_number_unsigned()) {
    const auto u = value_->get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(INT64_MAX)) return error("integer too large");
    return static_cast<std::int64_t>(u);
  }
  return error(std::string("expected an integer, found ") + type_name(*value_));
}

Result<bool> Field::as_bool() const {
  if (!value_->is_boolean()) return error(std::string("expected true or false, found ") + type_name(*value_));
  return value_->get<bool>();
}

Result<Duration> Field::as_duration() const {
  if (value_->is_number()) {
    const double s = value_->get<double>();
    if (!std::isfinite(s) || s < 0) return error("expected a duration of zero or more seconds");
    if (s > 9.0e12) return error("duration is too long");
    return from_seconds(s);
  }
  if (value_->is_string()) {
    auto d = parse_duration(value_->get<std::string>());
    if (!d) return error(d.error().message);
    return *d;
  }
  return error(std::string("expected a duration such as 90, \"90s\" or \"1h30m\", found ") + type_name(*value_));
}

Result<Time> Field::as_time(const TimeZone* zone) const {
  if (!value_->is_string()) {
    return error(std::string("expected an ISO 8601 time such as \"2026-11-23T08:45:00Z\", found ") +
                 type_name(*value_));
  }
  const std::string text = value_->get<std::string>();
  auto t = zone ? zone->parse_time(text) : parse_time(text);
  if (!t) {
    std::string msg = t.error().message;
    if (!zone && msg.find("has no zone") != std::string::npos) msg += ", or give the file a 'timezone'";
    return error(msg);
  }
  return *t;
}

Error Field::error(std::string_view what) const { return error_at("", what); }

std::string Field::where() const {
  std::string where = doc_.source();
  if (auto line = doc_.line_of(path_)) where += ":" + std::to_string(*line);
  if (!path_.empty()) where += ": " + path_;
  return where;
}

Error Field::error_at(std::string_view relative_path, std::string_view what) const {
  std::string path = path_;
  if (!relative_path.empty()) {
    path = (path.empty() || relative_path.front() == '[') ? path + std::string(relative_path)
                                                           : path + "." + std::string(relative_path);
  }
  std::string where = doc_.source();
  auto line = doc_.line_of(path);
  if (!line) line = doc_.line_of(path_);
  if (line) where += ":" + std::to_string(*line);
  where += ": ";
  if (!path.empty()) where += path + ": ";
  return Error::invalid(where + std::string(what));
}

namespace {
void emit(YAML::Emitter& out, const Json& v) {
  switch (v.type()) {
    case Json::value_t::object:
      out << YAML::BeginMap;
      for (auto it = v.begin(); it != v.end(); ++it) {
        out << YAML::Key << it.key() << YAML::Value;
        emit(out, it.value());
      }
      out << YAML::EndMap;
      break;
    case Json::value_t::array:
      out << YAML::BeginSeq;
      for (const auto& item : v) emit(out, item);
      out << YAML::EndSeq;
      break;
    case Json::value_t::string: {
      const auto& s = v.get_ref<const std::string&>();
      // Quote text that would read back as another type (a number, true, null...).
      if (!detail::plain_scalar(s).is_string() || s.empty()) {
        out << YAML::DoubleQuoted << s;
      } else {
        out << s;
      }
      break;
    }
    case Json::value_t::boolean: out << v.get<bool>(); break;
    case Json::value_t::number_integer: out << v.get<std::int64_t>(); break;
    case Json::value_t::number_unsigned: out << v.get<std::uint64_t>(); break;
    case Json::value_t::number_float: {
      // The shortest text that reads back as the same double.
      const double d = v.get<double>();
      std::string s = Json(d).dump();
      out << s;
      break;
    }
    default: out << YAML::Null; break;
  }
}
}  // namespace

std::string to_yaml(const Json& value) {
  YAML::Emitter out;
  emit(out, value);
  return std::string(out.c_str()) + "\n";
}

}  // namespace rondo
