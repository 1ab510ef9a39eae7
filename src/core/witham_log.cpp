#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

#include "rondo/core/document.h"
#include "rondo/core/traversal.h"
#include "rondo/core/utf8.h"

namespace rondo {
namespace {

// Splits "<From>_<To>" (node names in these logs have no underscore).
Result<std::pair<std::string, std::string>> edge_nodes(const std::filesystem::path& file) {
  const std::string stem = file.stem().string();
  // The name becomes the edge id, which reaches JSON output: it must be text.
  if (first_invalid_utf8(file.filename().native())) {
    return Error::invalid(printable_path(file) + ": the file name is not valid UTF-8");
  }
  const auto sep = stem.find('_');
  if (sep == std::string::npos || sep == 0 || sep + 1 == stem.size() || stem.find('_', sep + 1) != std::string::npos) {
    return Error::invalid(file.string() + ": file name must be <From>_<To>.data");
  }
  return std::pair{stem.substr(0, sep), stem.substr(sep + 1)};
}

template <class T>
bool read_number(std::string_view token, T& out) {
  auto [p, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
  return ec == std::errc{} && p == token.data() + token.size();
}

}  // namespace

Result<std::vector<Traversal>> read_witham_edge_log(const std::filesystem::path& file) {
  auto nodes = edge_nodes(file);
  if (!nodes) return nodes.error();
  auto text = read_text_file(file);
  if (!text) return text.error();
  const std::string name = file.filename().string();
  std::vector<Traversal> out;
  std::istringstream lines(*text);
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    std::istringstream words(line);
    std::string t, d, s, extra;
    words >> t >> d >> s;
    const auto where = file.string() + ":" + std::to_string(number) + ": ";
    if (s.empty() || (words >> extra)) {
      return Error::invalid(where + "expected 'unix_time duration_seconds success(0|1)', found '" +
                            quote_for_message(line) + "'");
    }
    double start = 0;
    double seconds_taken = 0;
    int ok = 0;
    if (!read_number(t, start) || !std::isfinite(start) || start < 0 || start > 1.0e11) {
      return Error::invalid(where + "start time '" + quote_for_message(t) + "' is not a unix time in seconds");
    }
    if (!read_number(d, seconds_taken) || !std::isfinite(seconds_taken) || seconds_taken < 0 || seconds_taken > 1.0e9) {
      return Error::invalid(where + "duration '" + quote_for_message(d) + "' is not a number of seconds >= 0");
    }
    if (!read_number(s, ok) || (ok != 0 && ok != 1)) {
      return Error::invalid(where + "success flag '" + quote_for_message(s) + "' must be 0 or 1");
    }
    out.push_back(Traversal{file.stem().string(), nodes->first, nodes->second, from_unix_seconds(start),
                            from_seconds(seconds_taken), ok == 1, "witham:" + name + ":" + std::to_string(number)});
  }
  return out;
}

Result<std::vector<Traversal>> read_witham_logs(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return Error::not_found(printable_path(dir) + ": no such folder");
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    if (entry.path().extension() == ".data") files.push_back(entry.path());
  }
  if (ec) return Error::io(dir.string() + ": " + ec.message());
  if (files.empty()) return Error::invalid(dir.string() + ": no <From>_<To>.data edge logs in this folder");
  std::sort(files.begin(), files.end());
  std::vector<Traversal> all;
  for (const auto& f : files) {
    auto part = read_witham_edge_log(f);
    if (!part) return part.error();
    all.insert(all.end(), std::make_move_iterator(part->begin()), std::make_move_iterator(part->end()));
  }
  std::stable_sort(all.begin(), all.end(), [](const Traversal& a, const Traversal& b) {
    return a.start != b.start ? a.start < b.start : a.edge_id < b.edge_id;
  });
  return all;
}

}  // namespace rondo
