// The words of a sentence, and the small word-level readers the grammar uses (clock times,
// counts, day names). Internal to rondo::lang.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/time.h"

namespace rondo::lang::detail {

struct Token {
  std::string text;  // as written, without surrounding punctuation: "A-110", "librarian's"
  std::string word;  // lower case, typographic apostrophes as ': "a-110", "librarian's"
  bool comma = false;  // a ',' came right after it ("A-110, A-111"): a list may go on there
};

using Tokens = std::vector<Token>;

// Splits on white space and drops punctuation around words ("urgent:" -> "urgent"). Words made
// only of punctuation are dropped.
Tokens tokenize(std::string_view sentence);

// The tokens [begin, end) as written, joined by single spaces.
std::string text_of(const Tokens& t, std::size_t begin, std::size_t end);

// "15:00", "9:30", "3pm", "9:30am", "noon": a time since midnight; nothing if it is not one.
std::optional<Duration> clock_time(std::string_view word);
// "monday".."sunday" (and "mon".."sun"), singular or plural ("mondays").
std::optional<std::chrono::weekday> weekday_named(std::string_view word);
// A whole number written in digits or as "one".."twelve".
std::optional<int> count_of(std::string_view word);
// "minute(s)", "min(s)", "hour(s)", "h", "hr(s)": the unit; nothing otherwise.
std::optional<Duration> unit_of(std::string_view word);

}  // namespace rondo::lang::detail
