#include "monitor.h"

#include <fmt/format.h>

#include "text.h"

namespace rondo::exec {

Monitor::Limit Monitor::limit(const char* what, const char* of, Duration expected, double factor, Duration slack) {
  const Duration after = std::chrono::duration_cast<Duration>(expected * factor) + slack;
  return {.after = after,
          .reason = fmt::format("{} after {}, the limit is {} x {} {} + {}", what, duration_text(after), factor, of,
                                duration_text(expected), duration_text(slack))};
}

void Monitor::arm(Limit limit, std::function<void(const std::string&)> fired) {
  cancel();
  reason_ = std::move(limit.reason);
  fired_ = std::move(fired);
  set(limit.after);
}

void Monitor::extend(Limit limit) {
  cancel();
  reason_ = std::move(limit.reason);
  set(limit.after);
}

void Monitor::set(Duration after) {
  at_ = clock_.now() + after;
  left_.reset();
  timer_ = clock_.schedule_after(after, [this] {
    timer_ = 0;
    fired_(reason_);
  });
}

void Monitor::cancel() {
  if (timer_ != 0) clock_.cancel(timer_);
  timer_ = 0;
  left_.reset();
}

void Monitor::suspend() {
  if (timer_ == 0) return;
  clock_.cancel(timer_);
  timer_ = 0;
  left_ = at_ - clock_.now();
}

std::optional<Time> Monitor::deadline() const {
  if (timer_ == 0) return std::nullopt;
  return at_;
}

void Monitor::resume() {
  if (!left_) return;
  set(*left_);
}

}  // namespace rondo::exec
