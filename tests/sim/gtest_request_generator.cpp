#include "rondo/sim/request_generator.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <set>
#include <string>

#include "sim_test_util.h"

namespace rondo::sim {
namespace {

using namespace rondo::sim::testing;

RequestGenerator g4s_people() {
  auto people = RequestGenerator::load("examples/g4s/requests.yaml", g4s_map(), london());
  EXPECT_TRUE(people.ok()) << (people.ok() ? "" : people.error().message);
  return std::move(people).value();
}

// Many requests a day from the one place "Hall", for the small map.
RequestSpec busy_hall(double per_day) {
  Task task;
  task.duration = minutes(1);
  task.actions = {Action{"talk", {}}};
  return RequestSpec{.per_day = per_day, .templates = {{.name = "t", .places = {"Hall"}, .task = task}}};
}

bool in_office_hours(Time t) {
  const auto wd = london().day_of_week(t);
  const auto tod = london().time_of_day(t);
  return wd != std::chrono::Saturday && wd != std::chrono::Sunday && tod >= hours(9) && tod < hours(17);
}

TEST(RequestGenerator, OnlyInOfficeHoursWithUniqueValidIds) {
  const auto people = g4s_people();
  Rng rng(1);
  // Four weeks across the October clock change: office hours stay 09:00-17:00 local.
  const Time from = local("2026-10-12T00:00");
  const Time to = local("2026-11-09T00:00");
  const auto requests = people.between(from, to, rng);
  // 20 office days at 4 a day on average.
  EXPECT_GT(requests.size(), 50u);
  EXPECT_LT(requests.size(), 120u);
  std::set<std::string> ids;
  Time previous = from;
  for (const Request& r : requests) {
    EXPECT_TRUE(in_office_hours(r.at)) << london().format_local(r.at);
    EXPECT_GE(r.at, previous);
    previous = r.at;
    EXPECT_TRUE(ids.insert(r.task.id).second) << r.task.id;
    EXPECT_EQ(r.task.kind, TaskKind::kOnDemand);
    EXPECT_TRUE(validate(r.task).ok());
    EXPECT_TRUE(g4s_map().find_node(r.task.start_node).has_value());
    EXPECT_FALSE(r.task.actions.empty());
  }
  EXPECT_EQ(requests.front().task.id.rfind("req-2026-10-", 0), 0u) << requests.front().task.id;
}

TEST(RequestGenerator, SameRngStateSameRequests) {
  const auto people = g4s_people();
  const Time from = local("2026-11-23T00:00");
  Rng a(5), b(5), c(6);
  const auto ra = people.between(from, from + std::chrono::days(7), a);
  const auto rb = people.between(from, from + std::chrono::days(7), b);
  const auto rc = people.between(from, from + std::chrono::days(7), c);
  ASSERT_EQ(ra.size(), rb.size());
  for (std::size_t i = 0; i < ra.size(); ++i) {
    EXPECT_EQ(ra[i].at, rb[i].at);
    EXPECT_EQ(ra[i].task, rb[i].task);
  }
  bool differs = ra.size() != rc.size();
  for (std::size_t i = 0; !differs && i < ra.size(); ++i) differs = ra[i].at != rc[i].at;
  EXPECT_TRUE(differs);
}

TEST(RequestGenerator, TheIdNamesTheLocalDateAndTime) {
  RequestGenerator people(busy_hall(2000), london());
  Rng rng(2);
  const auto requests = people.between(local("2026-07-01T10:00"), local("2026-07-01T10:05"), rng);
  ASSERT_FALSE(requests.empty());
  const Request& r = requests.front();
  const auto tod = std::chrono::duration_cast<std::chrono::seconds>(london().time_of_day(r.at)).count();
  char expected[64];
  std::snprintf(expected, sizeof expected, "req-2026-07-01-%02lld%02lld%02lld", static_cast<long long>(tod / 3600),
                static_cast<long long>(tod / 60 % 60), static_cast<long long>(tod % 60));
  EXPECT_EQ(r.task.id, expected);
  EXPECT_EQ(r.task.id.substr(0, 17), "req-2026-07-01-10");  // 10:0x local (BST), 09:0x UTC
}

// Splitting an interval into pieces never gives two requests one id, and all stay inside.
RC_GTEST_PROP(RequestGenerator, DisjointCallsNeverRepeatAnId, (std::uint64_t seed)) {
  RequestGenerator people(busy_hall(300), london());
  Rng rng(seed);
  std::set<std::string> ids;
  Time t = local("2026-11-23T08:00");
  const auto cuts = *rc::gen::container<std::vector<std::uint32_t>>(rc::gen::inRange<std::uint32_t>(1, 7200));
  for (std::uint32_t cut : cuts) {
    const Time next = t + seconds(cut);
    for (const Request& r : people.between(t, next, rng)) {
      RC_ASSERT(r.at >= t);
      RC_ASSERT(r.at < next);
      RC_ASSERT(ids.insert(r.task.id).second);
    }
    t = next;
  }
}

// A delivery template makes a linked pickup and drop, at two different places, in one window.
TEST(RequestGenerator, ADeliveryRequestIsAPickupAndADropOfOneJob) {
  auto doc = Document::parse(
      "per_day: 50\ntemplates:\n  - name: post\n    places: [Hall, Dock]\n    duration: 1m\n"
      "    deliver: {to: [Hall, Dock], objects: [letter, parcel], within: 90m}\n",
      DocumentFormat::kYaml, "requests.yaml");
  ASSERT_TRUE(doc.ok());
  auto people = RequestGenerator::decode(*doc, small_map(), london());
  ASSERT_TRUE(people.ok()) << people.error().message;
  Rng rng(3);
  const auto requests = people->between(local("2026-11-23T08:00"), local("2026-11-24T08:00"), rng);
  ASSERT_GT(requests.size(), 10u);
  for (const Request& r : requests) {
    ASSERT_TRUE(r.drop.has_value());
    const std::vector<Task> both = r.tasks();
    ASSERT_EQ(both.size(), 2u);
    EXPECT_TRUE(validate(both).ok()) << validate(both).error().message;
    const Task& p = both[0];
    const Task& d = both[1];
    EXPECT_EQ(p.kind, TaskKind::kStandard);
    EXPECT_EQ(p.delivery->role, DeliveryRole::kPickup);
    EXPECT_EQ(d.delivery->role, DeliveryRole::kDrop);
    EXPECT_EQ(p.delivery->job, d.delivery->job);
    EXPECT_EQ(p.id, p.delivery->job + "-pickup");
    EXPECT_NE(p.start_node, d.start_node);
    EXPECT_EQ(p.window, (TimeWindow{r.at, r.at + minutes(90)}));
    EXPECT_EQ(d.window, p.window);
    EXPECT_EQ(p.actions.front().name, "load");
    EXPECT_EQ(d.actions.front().name, "unload");
    EXPECT_EQ(d.actions.front().args.at("object"), d.delivery->object);
  }
}

struct BadRequests {
  const char* text;
  const char* message;
};

class RequestErrors : public ::testing::TestWithParam<BadRequests> {};

TEST_P(RequestErrors, NameTheFileLineAndField) {
  auto doc = Document::parse(GetParam().text, DocumentFormat::kYaml, "requests.yaml");
  ASSERT_TRUE(doc.ok());
  auto people = RequestGenerator::decode(*doc, small_map(), london());
  ASSERT_FALSE(people.ok());
  EXPECT_NE(people.error().message.find(GetParam().message), std::string::npos) << people.error().message;
}

INSTANTIATE_TEST_SUITE_P(
    Table, RequestErrors,
    ::testing::Values(
        BadRequests{"per_day: 3\n", "templates"},
        BadRequests{"from: \"17:00\"\nto: \"09:00\"\ntemplates: []\n", "requests.yaml:2: to: office hours must end"},
        BadRequests{"templates:\n  - name: t\n    places: [Hall, Attic]\n", "requests.yaml:3: templates[0].places[1]: map 'small' has no node 'Attic'"},
        BadRequests{"templates:\n  - name: t\n    places: [Hall]\n    colour: red\n", "colour"},
        BadRequests{"days: [someday]\ntemplates: []\n", "requests.yaml:1: days[0]: unknown day"},
        BadRequests{"per_day: -1\ntemplates: []\n", "requests.yaml:1: per_day: must be from 0"},
        BadRequests{"templates:\n  - name: t\n    places: [Hall]\n    deliver: {to: [Attic], objects: [x]}\n",
                    "requests.yaml:4: templates[0].deliver.to[0]: map 'small' has no node 'Attic'"},
        BadRequests{"templates:\n  - name: t\n    places: [Hall]\n    deliver: {to: [Hall], objects: [x]}\n",
                    "other than where it collects"},
        BadRequests{"templates:\n  - name: t\n    places: [Hall]\n    deliver: {to: [Dock], objects: []}\n",
                    "at least one kind of object"},
        BadRequests{"templates:\n  - name: t\n    places: [Hall]\n    deliver: {to: [Dock], objects: [x], by: 2h}\n",
                    "by"}));

}  // namespace
}  // namespace rondo::sim
