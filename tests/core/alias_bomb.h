// The "billion laughs" YAML: ten levels, each a list of ten aliases to the level above, so about
// 10^10 values once expanded from well under a kilobyte of text. Every loader must refuse it by
// counting (Document::kMaxValues), not by running out of time or memory.
#pragma once

#include <string>

namespace rondo::test {

inline std::string alias_bomb() {
  std::string text = "a0: &a0 lol\n";
  for (int level = 1; level < 10; ++level) {
    const std::string above = "*a" + std::to_string(level - 1);
    text += "a" + std::to_string(level) + ": &a" + std::to_string(level) + " [";
    for (int i = 0; i < 10; ++i) text += (i ? "," : "") + above;
    text += "]\n";
  }
  return text;
}

// The part of the refusal that names the counted limit.
inline const char* kAliasBombLimit = "more than 2000000 values once aliases are expanded (the limit is 2000000)";

}  // namespace rondo::test
