// Checks for the command line's whole-number options, run on an option's text before CLI11 reads
// it. CLI11 2.1 reads an integer with strtoll in base 0: past the type's range it clamps without a
// word (`--seed 99999999999999999999` ran with seed 9223372036854775807), "010" is octal 8 and
// "0x10" is 16. This takes decimal text only, refuses what is out of range with a message that
// names the option and the range (exit 2), and hands CLI11 the number written plainly:
//
//   run->add_option("--days", args->days, "Days to run")->transform(whole_number(1, 3660));
//   // rondo run --days 0   ->   rondo: error: --days: '0' is not a whole number from 1 to 3660
//
// Options that are real numbers are read by CLI11 with strtold, which refuses text that is not a
// number; their commands check the value (NaN and infinities included) against their range.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <limits>

namespace rondo::app {

inline constexpr std::int64_t kMaxWholeNumber = std::numeric_limits<std::int64_t>::max();

// Decimal whole numbers from `min` to `max`: an optional '-', digits, nothing else. Use it with
// Option::transform (it rewrites the text), not Option::check.
CLI::Validator whole_number(std::int64_t min, std::int64_t max);

}  // namespace rondo::app
