// Time and peak memory of refusing hostile YAML (issue 14): the 1 KB alias bomb and a document of
// many plain aliases, against an ordinary map. Prints one line per case with the machine's load;
// never part of the tests (they assert the counted limits, not time or memory).
//
//   build/bench/bench_document_limits
#include <sys/resource.h>

#include <cstdio>
#include <string>

#include "bench_clock.h"
#include "core/alias_bomb.h"
#include "rondo/core/document.h"

namespace {

long peak_rss_kb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

void run(const char* name, const std::string& text) {
  const double t0 = rondo::bench::steady_seconds();
  auto doc = rondo::Document::parse(text, rondo::DocumentFormat::kYaml, name);
  const double t1 = rondo::bench::steady_seconds();
  std::printf("%-22s %8zu bytes  %8.3f s  peak RSS so far %7ld KB  %s\n", name, text.size(), t1 - t0, peak_rss_kb(),
              doc.ok() ? "read" : doc.error().message.c_str());
}

}  // namespace

int main() {
  std::printf("load average %s\n", rondo::bench::load_average().c_str());
  std::string plain = "nodes:\n";
  for (int i = 0; i < 20000; ++i)
    plain += "  - {name: n" + std::to_string(i) + ", pose: {x: 1.5, y: 2.5}, edges: [a, b]}\n";
  run("ordinary 20000 nodes", plain);
  run("alias bomb", rondo::test::alias_bomb());
  std::string many = "a: &a [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]\nl:\n";
  for (int i = 0; i < 99000; ++i) many += "- *a\n";
  run("99000 aliases", many);
  return 0;
}
