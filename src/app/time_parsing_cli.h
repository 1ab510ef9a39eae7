// Parsing of command-line option values that are times and dates, with messages naming the option.
#pragma once

#include <chrono>
#include <string>

#include "rondo/core/result.h"
#include "rondo/core/time.h"

namespace rondo::app {

Result<std::chrono::year_month_day> parse_date_option(const std::string& option, const std::string& text);
Result<Time> parse_time_option(const std::string& option, const std::string& text);

}  // namespace rondo::app
