#include "map_locate.h"

#include <fmt/format.h>

#include <algorithm>

namespace rondo::map {

std::string quoted_name(const std::string& name) {
  constexpr std::size_t kMax = 60;
  std::size_t cut = std::min(name.size(), kMax);
  // Cut before a UTF-8 continuation byte, not inside a character.
  while (cut < name.size() && cut > 0 && (static_cast<unsigned char>(name[cut]) & 0xC0U) == 0x80U) --cut;
  std::string shown;
  for (char c : name.substr(0, cut)) {
    const auto u = static_cast<unsigned char>(c);
    shown += (u < 0x20 || u == 0x7f) ? '?' : c;
  }
  if (cut < name.size()) shown += "...";
  return "'" + shown + "'";
}

Error locate_problem(const Field& item, std::string_view field_path, std::string_view message,
                     std::size_t problem_count) {
  std::string what(message);
  if (problem_count > 1) what += fmt::format(" (and {} more problems)", problem_count - 1);
  return item.error_at(field_path, what);
}

}  // namespace rondo::map
