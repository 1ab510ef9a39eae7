#include <fmt/format.h>

#include <cctype>

#include "api.h"

namespace rondo::service {
namespace {

bool is_path_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '[' || c == ']';
}

// True for "tasks[0].window.deadline", "zone": what a field path looks like.
bool looks_like_path(std::string_view s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s)
    if (!is_path_char(c)) return false;
  return true;
}

const char* code_name(ErrorCode code) {
  switch (code) {
    case ErrorCode::kInvalidInput:
      return "invalid";
    case ErrorCode::kNotFound:
      return "not_found";
    case ErrorCode::kConflict:
      return "conflict";
    case ErrorCode::kUnsupported:
      return "unsupported";
    case ErrorCode::kIo:
    case ErrorCode::kStorage:
    case ErrorCode::kInternal:
      break;
  }
  return "internal";
}

}  // namespace

Reply error_reply(int status, std::string code, std::string message, std::string field) {
  Reply r;
  r.status = status;
  r.body = Json{{"error", Json{{"code", std::move(code)},
                               {"message", std::move(message)},
                               {"field", field.empty() ? Json(nullptr) : Json(std::move(field))}}}};
  return r;
}

std::string field_of(const std::string& message) {
  // "<source>:<line>: <path>: <what>" or "<source>: <path>: <what>"; the source has no spaces.
  std::vector<std::string_view> parts;
  std::string_view rest = message;
  for (int i = 0; i < 3 && !rest.empty(); ++i) {
    const std::size_t colon = rest.find(": ");
    const std::size_t end = colon == std::string_view::npos ? rest.size() : colon;
    std::string_view part = rest.substr(0, end);
    // "request:3" holds the line after the source.
    if (i == 0) {
      if (const std::size_t c = part.rfind(':'); c != std::string_view::npos) part = part.substr(0, c);
    }
    parts.push_back(part);
    if (colon == std::string_view::npos) break;
    rest.remove_prefix(colon + 2);
  }
  for (std::size_t i = 1; i < parts.size(); ++i)
    if (looks_like_path(parts[i])) return std::string(parts[i]);
  return "";
}

Reply error_reply(const Error& error) {
  int status = 500;
  switch (error.code) {
    case ErrorCode::kInvalidInput:
      status = 422;
      break;
    case ErrorCode::kNotFound:
      status = 404;
      break;
    case ErrorCode::kConflict:
      status = 409;
      break;
    case ErrorCode::kUnsupported:
      status = 501;
      break;
    default:
      break;
  }
  return error_reply(status, code_name(error.code), error.message,
                     error.code == ErrorCode::kInvalidInput ? field_of(error.message) : "");
}

}  // namespace rondo::service
