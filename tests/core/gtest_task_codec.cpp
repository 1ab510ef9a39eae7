#include "rondo/core/task_codec.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "core/task_generators.h"

namespace rondo {
namespace {

Result<TaskFile> parse_yaml(const std::string& text) {
  return parse_task_file(text, DocumentFormat::kYaml, "day.yaml");
}

TEST(TaskCodec, ReadsTheExampleFile) {
  auto file = load_task_file("tests/data/tasks/office_day.yaml");
  ASSERT_TRUE(file.ok()) << file.error().message;
  ASSERT_EQ(file->tasks.size(), 3u);
  ASSERT_EQ(file->routines.size(), 2u);
  const Task& pickup = file->tasks[0];
  EXPECT_EQ(pickup.delivery->role, DeliveryRole::kPickup);
  EXPECT_EQ(pickup.delivery->appearance, "green book");  // defaults to the object
  EXPECT_EQ(format_time(pickup.window->release), "2026-11-23T09:00:00Z");  // local winter time = UTC
  const Task& greet = file->tasks[2];
  EXPECT_EQ(greet.kind, TaskKind::kOnDemand);
  EXPECT_FALSE(greet.interruptible);
  EXPECT_EQ(greet.actions[0].args.at("volume"), "0.8");
  EXPECT_EQ(file->routines[1].days.size(), 5u);  // days_off sat, sun
}

TEST(TaskCodec, MalformedFilesNameWhereAndWhat) {
  struct Case {
    const char* name;
    std::string text;
    std::string expect;  // the whole message, or its start
  };
  const std::string head = "tasks:\n  - id: a\n";
  const Case cases[] = {
      {"truncated yaml", "tasks:\n  - id: a\n    window: {release: 2026-11-23T09:00Z", "day.yaml:3: "},
      {"empty file", "", "day.yaml: the file is empty"},
      {"not a mapping", "- 1\n- 2\n", "day.yaml:1: expected a mapping"},
      {"unknown top-level field", "taks: []\n", "day.yaml:1: taks: unknown field 'taks'"},
      {"unknown task field", head + "    prio: 3\n", "day.yaml:3: tasks[0].prio: unknown field 'prio'"},
      {"wrong type", head + "    kind: on-demand\n    priority: [1]\n",
       "day.yaml:4: tasks[0].priority: expected an integer, found a list"},
      {"bad duration", head + "    kind: on-demand\n    duration: soon\n", "day.yaml:4: tasks[0].duration: duration 'soon'"},
      {"window ends before it starts",
       head + "    window: {release: 2026-11-23T10:00Z, deadline: 2026-11-23T09:00Z}\n",
       "day.yaml:3: tasks[0].window.deadline: deadline 2026-11-23T09:00:00Z is before the release 2026-11-23T10:00:00Z"},
      {"local time without zone", head + "    window: {release: 2026-11-23T09:00, deadline: 2026-11-23T10:00}\n",
       "day.yaml:3: tasks[0].window.release: time '2026-11-23T09:00' has no zone"},
      {"unknown time zone", "timezone: Europe/Lincoln\n", "day.yaml:1: timezone: time zone 'Europe/Lincoln'"},
      {"missing id", "tasks:\n  - kind: on-demand\n", "day.yaml:2: tasks[0]: missing field 'id'"},
      {"unknown kind", head + "    kind: urgent\n", "day.yaml:3: tasks[0].kind: unknown task kind 'urgent'"},
      {"empty robot", head + "    kind: on-demand\n    robot: ''\n",
       "day.yaml:4: tasks[0].robot: a robot's name must not be empty"},
      {"after unknown", head + "    kind: on-demand\n    after: [b]\n", "day.yaml:4: tasks[0].after[0]: no task 'b'"},
      {"routines without zone", "routines: []\n", "day.yaml:1: routines: routines run at local times"},
      {"routine window backwards",
       "timezone: UTC\nroutines:\n  - name: r\n    task: {duration: 1m}\n    window: {from: \"11:00\", to: \"09:00\"}\n",
       "day.yaml:5: routines[0].window.to: the daily window must close after it opens (opens 11:00, closes 09:00)"},
      {"routine bad day",
       "timezone: UTC\nroutines:\n  - name: r\n    task: {}\n    window: {from: \"09:00\", to: \"10:00\"}\n    days: [mon, funday]\n",
       "day.yaml:6: routines[0].days[1]: unknown day 'funday'"},
      {"routine template with id",
       "timezone: UTC\nroutines:\n  - name: r\n    task: {id: x}\n    window: {from: \"09:00\", to: \"10:00\"}\n",
       "day.yaml:4: routines[0].task.id: unknown field 'id'"},
      {"routine days and days off",
       "timezone: UTC\nroutines:\n  - name: r\n    task: {}\n    window: {from: \"09:00\", to: \"10:00\"}\n"
       "    days: [mon]\n    days_off: [sun]\n",
       "day.yaml:7: routines[0].days_off: give either"},
      {"duplicate routine",
       "timezone: UTC\nroutines:\n  - {name: r, task: {}, window: {from: \"09:00\", to: \"10:00\"}}\n"
       "  - {name: r, task: {}, window: {from: \"09:00\", to: \"10:00\"}}\n",
       "day.yaml:4: routines[1].name: duplicate routine name 'r'"},
  };
  for (const auto& c : cases) {
    auto file = parse_yaml(c.text);
    ASSERT_FALSE(file.ok()) << c.name;
    EXPECT_EQ(file.error().code, ErrorCode::kInvalidInput) << c.name;
    EXPECT_EQ(file.error().message.rfind(c.expect, 0), 0u) << c.name << ":\n  got:    " << file.error().message
                                                          << "\n  wanted: " << c.expect;
  }
}

TEST(TaskCodec, SpecTasksRoundTrip) {
  const std::string text =
      "tasks:\n  - id: rounds\n    window: {release: 2026-11-23T09:00Z, deadline: 2026-11-23T12:00Z}\n"
      "    duration: 2m\n    spec: '!WayPoint12 U Station'\n    actions: [check_door]\n"
      "routines:\n  - name: doors\n    task: {duration: 1m, spec: F A & F B}\n    window: {from: \"08:00\", to: "
      "\"10:00\"}\ntimezone: UTC\n";
  auto file = parse_yaml(text);
  ASSERT_TRUE(file.ok()) << file.error().message;
  EXPECT_EQ(file->tasks[0].spec, "!WayPoint12 U Station");
  EXPECT_TRUE(file->tasks[0].has_spec());
  EXPECT_TRUE(file->tasks[0].start_node.empty());
  EXPECT_EQ(file->routines[0].task.spec, "F A & F B");
  auto back = parse_task_file(encode(*file).dump(), DocumentFormat::kJson, "back.json");
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ(back->tasks, file->tasks);
  EXPECT_EQ(back->routines[0].task, file->routines[0].task);
}

TEST(TaskCodec, SpecTasksRefuseWhatCannotBeMeant) {
  const std::string head = "tasks:\n  - id: a\n    kind: on-demand\n";
  const std::pair<std::string, std::string> cases[] = {
      {head + "    spec: F A\n    start_node: A\n",
       "day.yaml:4: tasks[0].spec: a task has a spec or a start_node, not both"},
      {head + "    spec: F A\n    end_node: A\n", "day.yaml:5: tasks[0].end_node: a spec task ends where"},
      {head + "    spec: ''\n", "day.yaml:4: tasks[0].spec: a spec is a formula over the map's nodes"},
      {head + "    spec: [F A]\n", "day.yaml:4: tasks[0].spec: expected text, found a list"},
  };
  for (const auto& [text, expect] : cases) {
    auto file = parse_yaml(text);
    ASSERT_FALSE(file.ok()) << text;
    EXPECT_EQ(file.error().message.substr(0, expect.size()), expect) << file.error().message;
  }
  // The formula's own check (ltl's, injected: core cannot read formulas) speaks at the field.
  const PlaceCheck check{.known = {}, .map_name = {}, .spec = [](std::string_view f) -> Status {
                           if (f == "G A") return Error::invalid("position 1: 'G' (always) is outside the fragment");
                           return {};
                         }};
  auto refused = parse_task_file(head + "    spec: G A\n", DocumentFormat::kYaml, "day.yaml", &check);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().message, "day.yaml:4: tasks[0].spec: position 1: 'G' (always) is outside the fragment");
  EXPECT_TRUE(parse_task_file(head + "    spec: F A\n", DocumentFormat::kYaml, "day.yaml", &check).ok());
}

TEST(TaskCodec, JsonFilesReadLikeYaml) {
  const std::string json = R"({"tasks": [{"id": "a", "window": {"release": "2026-11-23T09:00:00Z",
     "deadline": "2026-11-23T10:00:00Z"}, "duration": 60, "start_node": "A"}]})";
  auto file = parse_task_file(json, DocumentFormat::kJson, "day.json");
  ASSERT_TRUE(file.ok()) << file.error().message;
  EXPECT_EQ(file->tasks[0].duration, minutes(1));
  auto bad = parse_task_file(R"({"tasks": [{"id": 5}]})", DocumentFormat::kJson, "day.json");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message, "day.json: tasks[0].id: expected text, found an integer");
  // A key twice: refused, as in YAML, not the last one taken.
  auto twice = parse_task_file(R"({"tasks": [{"id": "a", "window": {"release": "2026-11-23T09:00:00Z",
     "deadline": "2026-11-23T10:00:00Z"}, "duration": 60, "duration": 120, "start_node": "A"}]})",
                               DocumentFormat::kJson, "day.json");
  ASSERT_FALSE(twice.ok());
  EXPECT_EQ(twice.error().message, "day.json:2: tasks[0].duration: duplicate key 'duration'");
}

RC_GTEST_PROP(TaskCodec, EncodeThenDecodeIsIdentityInYamlAndJson, ()) {
  const TaskFile file = *test::gen_task_file();
  const Json j = encode(file);
  for (auto format : {DocumentFormat::kYaml, DocumentFormat::kJson}) {
    const std::string text = format == DocumentFormat::kYaml ? to_yaml(j) : j.dump();
    auto back = parse_task_file(text, format, "gen");
    RC_ASSERT(back.ok());
    RC_ASSERT(back->tasks == file.tasks);
    RC_ASSERT(back->routines == file.routines);
    RC_ASSERT(back->zone == file.zone);
  }
}

RC_GTEST_PROP(TaskCodec, RoutineInstancesAreValidTasksInsideTheDailyWindow, ()) {
  const TaskFile file = *test::gen_task_file();
  const std::chrono::year_month_day day{std::chrono::year{2026}, std::chrono::March,
                                        std::chrono::day{*rc::gen::inRange(20u, 31u)}};  // around a DST change
  for (const auto& r : file.routines) {
    for (const auto& t : instances_on(r, day, *file.zone)) {
      RC_ASSERT(validate(t).ok());
      RC_ASSERT(file.zone->local_date(t.window->release) == day);
      RC_ASSERT(t.duration <= t.window->width());
    }
  }
}

}  // namespace
}  // namespace rondo
