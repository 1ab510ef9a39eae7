#include "rondo/core/utf8.h"

#include <algorithm>

namespace rondo {
namespace {

// The length of the well-formed UTF-8 sequence at text[i], or 0 if there is none.
std::size_t sequence_length(std::string_view text, std::size_t i) {
  const auto c = static_cast<unsigned char>(text[i]);
  if (c < 0x80) return 1;
  std::size_t len = 0;
  unsigned min = 0;
  unsigned code = 0;
  if ((c & 0xE0U) == 0xC0U) {
    len = 2, min = 0x80, code = c & 0x1FU;
  } else if ((c & 0xF0U) == 0xE0U) {
    len = 3, min = 0x800, code = c & 0x0FU;
  } else if ((c & 0xF8U) == 0xF0U) {
    len = 4, min = 0x10000, code = c & 0x07U;
  } else {
    return 0;
  }
  if (i + len > text.size()) return 0;
  for (std::size_t k = 1; k < len; ++k) {
    const auto cc = static_cast<unsigned char>(text[i + k]);
    if ((cc & 0xC0U) != 0x80U) return 0;
    code = (code << 6U) | (cc & 0x3FU);
  }
  if (code < min || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return 0;
  return len;
}

}  // namespace

std::optional<std::size_t> first_invalid_utf8(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t len = sequence_length(text, i);
    if (len == 0) return i;
    i += len;
  }
  return std::nullopt;
}

std::string replace_invalid_utf8(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t len = sequence_length(text, i);
    if (len == 0) {
      out += '?';
      ++i;
    } else {
      out.append(text.substr(i, len));
      i += len;
    }
  }
  return out;
}

std::string quote_for_message(std::string_view text, std::size_t max_chars) {
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t len = sequence_length(text, i);
    if (out.size() + std::max<std::size_t>(len, 1) > max_chars) {
      out += "...";
      break;
    }
    const auto c = static_cast<unsigned char>(text[i]);
    if (len == 0 || (len == 1 && (c < 0x20 || c == 0x7f))) {
      out += '?';
      i += 1;
    } else {
      out.append(text.substr(i, len));
      i += len;
    }
  }
  return out;
}

std::string printable_path(const std::filesystem::path& path) {
  return replace_invalid_utf8(path.native());
}

}  // namespace rondo
