// RapidCheck generators of valid tasks, routines and task files, for property tests.
#pragma once

#include <rapidcheck.h>

#include "rondo/core/task_codec.h"

namespace rondo::test {

inline rc::Gen<std::string> gen_name() {
  return rc::gen::map(rc::gen::inRange(0, 10000), [](int i) { return "n" + std::to_string(i); });
}

inline rc::Gen<Task> gen_task(std::string id) {
  return rc::gen::exec([id] {
    Task t;
    t.id = id;
    t.activity = *rc::gen::element<std::string>("", "check the door", "say: \"hello\" #1", "12", "true");
    t.kind = *rc::gen::element(TaskKind::kStandard, TaskKind::kOnDemand);
    t.duration = Duration{*rc::gen::inRange<std::int64_t>(0, 4 * 3600 * 1000)};
    if (t.kind == TaskKind::kStandard) {
      const Time release{Duration{*rc::gen::inRange<std::int64_t>(1'500'000'000'000, 1'900'000'000'000)}};
      const Duration slack{*rc::gen::inRange<std::int64_t>(0, 8 * 3600 * 1000)};
      t.window = TimeWindow{release, release + t.duration + slack};
    }
    t.priority = *rc::gen::inRange(-5, 20);
    if (*rc::gen::arbitrary<bool>()) {
      t.start_node = *gen_name();
      if (*rc::gen::arbitrary<bool>()) t.end_node = *gen_name();
    }
    const int n_actions = *rc::gen::inRange(0, 3);
    for (int i = 0; i < n_actions; ++i) {
      Action a{*rc::gen::element<std::string>("say", "look", "dock"), {}};
      if (*rc::gen::arbitrary<bool>()) a.args["text"] = *rc::gen::element<std::string>("hi", "0.5", "null", "a: b");
      t.actions.push_back(std::move(a));
    }
    t.interruptible = *rc::gen::arbitrary<bool>();
    if (*rc::gen::arbitrary<bool>()) t.robot = *rc::gen::element<std::string>("r1", "robot", "Tug 2");
    return t;
  });
}

inline rc::Gen<Routine> gen_routine(std::string name) {
  return rc::gen::exec([name] {
    Routine r;
    r.name = name;
    const int start_min = *rc::gen::inRange(0, 23 * 60);
    const int end_min = *rc::gen::inRange(start_min + 1, 24 * 60 + 1);
    r.window_start = minutes(start_min);
    r.window_end = minutes(end_min);
    const Duration window = r.window_end - r.window_start;
    if (*rc::gen::arbitrary<bool>()) r.every = minutes(*rc::gen::inRange<int>(1, end_min - start_min + 1));
    const Duration slot = r.every.value_or(window);
    r.task.activity = "routine work";
    r.task.duration = minutes(*rc::gen::inRange<std::int64_t>(0, slot.count() / 60000 + 1));
    r.task.start_node = *gen_name();
    const int n_days = *rc::gen::inRange(0, 7);
    for (unsigned d = 1; d <= static_cast<unsigned>(n_days); ++d) r.days.emplace_back(d);  // Monday first
    if (*rc::gen::arbitrary<bool>()) r.dates_off = {std::chrono::year{2026} / 12 / 25};
    return r;
  });
}

inline rc::Gen<TaskFile> gen_task_file() {
  return rc::gen::exec([] {
    TaskFile f;
    f.zone = *TimeZone::named(*rc::gen::element<std::string>("UTC", "Europe/London", "America/New_York"));
    const int n = *rc::gen::inRange(0, 6);
    for (int i = 0; i < n; ++i) f.tasks.push_back(*gen_task("t" + std::to_string(i)));
    const int m = *rc::gen::inRange(0, 3);
    for (int i = 0; i < m; ++i) f.routines.push_back(*gen_routine("r" + std::to_string(i)));
    return f;
  });
}

}  // namespace rondo::test
