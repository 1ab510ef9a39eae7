#include "rondo/ltl/task_formula.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace rondo::ltl {
namespace {

TEST(TaskFormula, RefusalsNameWhereAndWhy) {
  const std::set<std::string> map{"A", "B", "Station"};
  const KnownNode known = [&map](std::string_view n) { return map.contains(std::string(n)); };
  struct Case {
    const char* text;
    const char* expect;  // the message's start
  };
  const Case cases[] = {
      {"G A", "position 1: 'G' (always) is outside the co-safe fragment"},
      {"F A & !F B", "position 7: '!' applies to a node only"},
      {"F A & F Lab", "the formula names 'Lab', which is not on the map 'office'"},
      {"F a & F b & F c & F d & F e & F f & F g & F h & F i", "the formula"},
  };
  for (const Case& c : cases) {
    auto a = task_automaton(
        c.text, std::string_view(c.text).find("Lab") != std::string_view::npos ? known : KnownNode{}, "office");
    ASSERT_FALSE(a.ok()) << c.text;
    EXPECT_EQ(a.error().message.substr(0, std::string(c.expect).size()), c.expect) << a.error().message;
    EXPECT_FALSE(check_task_formula(c.text).ok() && std::string_view(c.text).find("Lab") == std::string_view::npos);
  }
  auto ok = task_automaton("!B U Station", known, "office");
  ASSERT_TRUE(ok.ok()) << ok.error().message;
  EXPECT_EQ((*ok)->state_count(), 3u);
}

}  // namespace
}  // namespace rondo::ltl
