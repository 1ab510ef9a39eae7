#include "number_options.h"

#include <fmt/format.h>

#include <charconv>
#include <string>

#include "rondo/core/utf8.h"

namespace rondo::app {

CLI::Validator whole_number(std::int64_t min, std::int64_t max) {
  const std::string range = fmt::format("from {} to {}", min, max);
  return CLI::Validator(
      [min, max, range](std::string& text) -> std::string {
        std::int64_t value = 0;
        const char* last = text.data() + text.size();
        const auto [end, error] = std::from_chars(text.data(), last, value);
        if (error != std::errc{} || end != last || value < min || value > max)
          return fmt::format("'{}' is not a whole number {}", quote_for_message(text), range);
        text = std::to_string(value);  // what CLI11 reads next: no leading zero for it to take as octal
        return {};
      },
      "INT " + range);
}

}  // namespace rondo::app
