// Normalisation, slugs and edit distance (rondo/lang/words.h); the distance against a slow,
// obviously correct recursive definition on small inputs.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <functional>

#include "rondo/lang/words.h"

namespace rondo::lang {
namespace {

TEST(Words, NormaliseDropsCaseArticlesAndRoomWords) {
  EXPECT_EQ(normalise_phrase("The Librarian's desk in Room A-110"), "librarian's desk in a-110");
  EXPECT_EQ(normalise_phrase("  office   A-123. "), "a-123");
  EXPECT_EQ(normalise_phrase("Michael\u2019s desk"), "michael's desk");
  EXPECT_EQ(normalise_phrase("an (east) exit,"), "east exit");
  EXPECT_EQ(normalise_phrase("Office"), "office");  // only filler: kept
  EXPECT_EQ(normalise_phrase("The Room"), "the room");
  EXPECT_EQ(normalise_phrase(""), "");
  EXPECT_EQ(normalise_phrase("\t\n"), "");
}

TEST(Words, ObjectsKeepEveryWordButALeadingArticle) {
  EXPECT_EQ(normalise_object("The Office Chair"), "office chair");
  EXPECT_EQ(normalise_object("a Red  Letter."), "red letter");
  EXPECT_EQ(normalise_object("the"), "");
}

TEST(Words, SlugIsLowerCaseDashed) {
  EXPECT_EQ(slug("Exit-West"), "exit-west");
  EXPECT_EQ(slug("red letter"), "red-letter");
  EXPECT_EQ(slug("  A--110 / desk "), "a-110-desk");
  EXPECT_EQ(slug("?!"), "x");
}

std::size_t reference_distance(const std::string& a, const std::string& b) {
  std::function<std::size_t(std::size_t, std::size_t)> d = [&](std::size_t i, std::size_t j) -> std::size_t {
    if (i == 0) return j;
    if (j == 0) return i;
    return std::min({d(i - 1, j) + 1, d(i, j - 1) + 1, d(i - 1, j - 1) + (a[i - 1] == b[j - 1] ? 0 : 1)});
  };
  return d(a.size(), b.size());
}

std::string small_word(const std::vector<int>& codes) {
  std::string s;
  for (int c : codes) s.push_back(static_cast<char>('a' + (c % 3 + 3) % 3));  // a, b, c: many repeats
  return s.substr(0, 7);
}

RC_GTEST_PROP(Words, EditDistanceMatchesTheRecursiveDefinition,
              (const std::vector<int>& x, const std::vector<int>& y)) {
  const std::string a = small_word(x);
  const std::string b = small_word(y);
  RC_ASSERT(edit_distance(a, b) == reference_distance(a, b));
  RC_ASSERT(edit_distance(a, b) == edit_distance(b, a));
  RC_ASSERT(edit_distance(a, a) == 0u);
  const std::size_t cap = 2;
  RC_ASSERT(edit_distance(a, b, cap) == std::min(reference_distance(a, b), cap));
}

TEST(Words, NearestRanksByDistanceThenOrder) {
  const std::vector<std::string> names = {"a-111", "a-120", "kitchen", "a-123", "a-120"};
  EXPECT_EQ(nearest("a-121", names, 3), (std::vector<std::string>{"a-120", "a-123", "a-111"}));
  EXPECT_EQ(nearest("kitchn", names, 1), (std::vector<std::string>{"kitchen"}));
  EXPECT_EQ(nearest("x", {}, 3), std::vector<std::string>{});
  EXPECT_EQ(nearest("desk in a-123", {"hall-a-123", "a-123", "a-123-desk"}, 1), std::vector<std::string>{"a-123-desk"});
}

}  // namespace
}  // namespace rondo::lang
