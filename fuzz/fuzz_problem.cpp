// libFuzzer target: schedule problem files (src/schedule/problem_codec.cpp), YAML and JSON by the
// first byte; what decodes validates and encodes to JSON that is text.
#include "fuzz_support.h"
#include "rondo/core/document.h"
#include "rondo/schedule/problem_codec.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto format = data[0] == '{' ? rondo::DocumentFormat::kJson : rondo::DocumentFormat::kYaml;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto doc = rondo::Document::parse(text, format, "problem");
  if (!doc) return rondo::fuzz::check_error(doc.error()), 0;
  auto p = rondo::schedule::decode_problem(*doc);
  if (!p) return rondo::fuzz::check_error(p.error()), 0;
  if (auto ok = rondo::schedule::validate(*p); !ok)
    rondo::fuzz::broken("a decoded problem fails validate", ok.error().message);
  return 0;
}
