// Validation of messages against the official VDA 5050 2.0.0 JSON schemas, read in place from
// ../shared/data/vda5050/2.0.0/json_schemas (with valijson, libvalijson-dev).
//
//   SchemaCheck check = SchemaCheck::load("order", Strictness::kStandardShape);
//   EXPECT_EQ(check.problems(encode_order(h, o)), "");   // "" when it validates
//
// The known defects of the 2.0.0 schema files (../shared/data/vda5050/README.md) are patched in
// ONE place, patch_known_defects() in schema_check.cpp; see there.
#pragma once

#include <memory>
#include <string>

#include "rondo/core/document.h"

namespace rondo::vda5050::testing {

enum class Strictness {
  kSchema,         // the schema as published (patched), which allows any extra key
  kStandardShape,  // and no key beyond those it defines (additionalProperties: false everywhere)
};

class SchemaCheck {
 public:
  // `name` is the schema file's stem: "order", "instantActions", "state", "connection".
  static SchemaCheck load(const std::string& name, Strictness strictness);
  ~SchemaCheck();
  SchemaCheck(SchemaCheck&&) noexcept;

  // "" when `message` validates, else every violation, one per line, with its JSON path.
  std::string problems(const Json& message) const;

 private:
  SchemaCheck();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rondo::vda5050::testing
