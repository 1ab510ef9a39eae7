// The week learned live (issue 37, point 2). The nightly refit fits the edge models from the last
// `refit_window` of the traversal log, too few weeks for a time-of-week term. Beside it the
// building keeps a learn::WeeklyMemory: each night it adds the whole local days since the last
// refit (one day's traversals, read by time range: the same work every night however long the
// robot has lived), saves the memory in the store's meta table, and gives the refitted models the
// term the memory chooses for each edge. A restart reads the memory back and adds only the days it
// had not seen.
#include <fmt/format.h>

#include <map>

#include "rondo/core/document.h"
#include "rondo/exec/building.h"
#include "rondo/learn/edge_models.h"
#include "rondo/learn/weekly_memory.h"
#include "rondo/store/robot_state.h"
#include "rondo/store/traversal_log.h"

namespace rondo::exec {
namespace {

constexpr std::string_view kMemoryKey = "learn.weekly_memory";

std::chrono::year_month_day date_of(std::int64_t day) {
  return std::chrono::year_month_day{std::chrono::sys_days{std::chrono::days{day}}};
}

}  // namespace

std::shared_ptr<const learn::EdgeModels> Building::with_week(std::shared_ptr<const learn::EdgeModels> fitted) {
  if (!options.weekly_half_life) return fitted;
  const learn::WeeklyMemoryOptions wanted{.half_life_days = to_seconds(*options.weekly_half_life) / 86400.0};
  if (!weekly_memory) {
    weekly_memory = std::make_unique<learn::WeeklyMemory>(wanted);
    auto stored = store::get_meta(store, kMemoryKey);
    if (!stored) {
      book.write_error(stored.error().message);
    } else if (*stored) {
      const Json j = Json::parse(**stored, nullptr, /*allow_exceptions=*/false);
      auto memory = j.is_discarded() ? Result<learn::WeeklyMemory>(Error::invalid("weekly memory: not JSON"))
                                     : learn::WeeklyMemory::from_json(j);
      if (!memory)
        book.write_error(fmt::format("the stored weekly memory is not used, the week is learned afresh: {}",
                                     memory.error().message));
      else if (memory->options().half_life_days == wanted.half_life_days)
        *weekly_memory = std::move(*memory);  // a memory forgotten at another rate starts afresh
    }
  }
  learn::WeeklyMemory& memory = *weekly_memory;
  const learn::EpisodePriors& priors = fitted->priors();
  const std::int64_t today = std::chrono::sys_days{zone.local_date(clock.now())}.time_since_epoch().count();
  // A new memory starts from the days it can still use; one that missed days skips to them.
  const std::int64_t oldest = today - 7 * memory.options().weeks_kept;
  const std::int64_t first = std::max(memory.next_day().value_or(oldest), oldest);
  if (first >= today) return fitted->with_weekly(memory);
  store::TraversalQuery query{.from = zone.at(date_of(first), Duration{0}),
                              .until = zone.at(date_of(today), Duration{0})};
  auto log = store::find_traversals(store, query);
  if (!log) {
    book.write_error(log.error().message);
    return fitted->with_weekly(memory);
  }
  std::map<std::int64_t, std::vector<Traversal>> days;
  for (Traversal& t : *log) days[priors.slot_attempt(t.start, t.success).day].push_back(std::move(t));
  for (std::int64_t day = first; day < today; ++day) {
    const auto it = days.find(day);
    const std::span<const Traversal> traversals =
        it == days.end() ? std::span<const Traversal>{} : std::span<const Traversal>{it->second};
    if (auto added = memory.add_day(day, traversals, priors); !added) {
      book.write_error(added.error().message);
      break;
    }
  }
  if (auto saved = store::set_meta(store, kMemoryKey, memory.to_json().dump()); !saved)
    book.write_error(saved.error().message);
  return fitted->with_weekly(memory);
}

}  // namespace rondo::exec
