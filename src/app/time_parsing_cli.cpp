#include "time_parsing_cli.h"



namespace rondo::app {

Result<std::chrono::year_month_day> parse_date_option(const std::string& option, const std::string& text) {
  auto t = parse_time(text + "T00:00:00Z");
  if (!t || text.size() != 10) return Error::invalid(option + ": expected a date YYYY-MM-DD, got '" + text + "'");
  return std::chrono::year_month_day{std::chrono::floor<std::chrono::days>(*t)};
}

Result<Time> parse_time_option(const std::string& option, const std::string& text) {
  auto t = parse_time(text);
  if (!t) return Error::invalid(option + ": " + t.error().message);
  return *t;
}

}  // namespace rondo::app
