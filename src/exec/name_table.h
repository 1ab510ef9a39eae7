// An enum's names, in one constexpr table: the name of a value, the value of a name, and every
// value in declaration order. Internal to rondo::exec (outcome.cpp, event_kind.cpp).
//
//   constexpr NameTable<Outcome, 2> kTable{{{{Outcome::kNone, ""}, {Outcome::kAdded, "added"}}}};
//   kTable.name(Outcome::kAdded);  kTable.parse("added");  kTable.values;
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>
#include <utility>

namespace rondo::exec {

template <class E, std::size_t N>
struct NameTable {
  constexpr explicit NameTable(std::array<std::pair<E, std::string_view>, N> n) : names(n) {
    for (std::size_t i = 0; i < N; ++i) values[i] = names[i].first;
  }
  constexpr std::string_view name(E e) const {
    for (const auto& [value, text] : names)
      if (value == e) return text;
    return "";
  }
  constexpr std::optional<E> parse(std::string_view text) const {
    for (const auto& [value, t] : names)
      if (t == text) return value;
    return std::nullopt;
  }
  std::array<std::pair<E, std::string_view>, N> names;
  std::array<E, N> values{};
};

}  // namespace rondo::exec
