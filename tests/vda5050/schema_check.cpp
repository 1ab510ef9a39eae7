#include "vda5050/schema_check.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>
#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validator.hpp>

namespace rondo::vda5050::testing {
namespace {

const char* kSchemaDir = "../shared/data/vda5050/2.0.0/json_schemas/";

// THE ONE PLACE where the known defects of the 2.0.0 schema files are patched (fixed upstream in
// 2.1.0; listed in ../shared/data/vda5050/README.md). Each patch makes the file say what the
// specification's text (VDA5050_EN.md) says:
//  1. instantActions.schema has no top-level `required`: the header fields and `actions` are
//     required, as in every other message.
//  2. instantActions.schema's action requires and defines `actionName`; the document and
//     order.schema call it `actionType`.
//  3. order.schema spells the node position's `allowedDeviationXy`; the document says
//     `allowedDeviationXY`.
void patch_known_defects(const std::string& name, nlohmann::json& schema) {
  if (name == "instantActions") {
    schema["required"] = {"headerId", "timestamp", "version", "manufacturer", "serialNumber", "actions"};
    auto& action = schema["properties"]["actions"]["items"];
    for (auto& r : action["required"]) {
      if (r == "actionName") r = "actionType";
    }
    action["properties"]["actionType"] = action["properties"]["actionName"];
    action["properties"].erase("actionName");
  }
  if (name == "order") {
    auto& pos = schema["properties"]["nodes"]["items"]["properties"]["nodePosition"]["properties"];
    pos["allowedDeviationXY"] = pos["allowedDeviationXy"];
    pos.erase("allowedDeviationXy");
  }
}

// Every object schema that lists its properties admits no other key.
void forbid_extra_keys(nlohmann::json& schema) {
  if (schema.is_object()) {
    if (schema.contains("properties") && schema["properties"].is_object()) {
      schema["additionalProperties"] = false;
    }
    for (auto& [key, value] : schema.items()) {
      if (key != "examples") forbid_extra_keys(value);
    }
  } else if (schema.is_array()) {
    for (auto& v : schema) forbid_extra_keys(v);
  }
}

}  // namespace

struct SchemaCheck::Impl {
  nlohmann::json document;
  valijson::Schema schema;
};

SchemaCheck::SchemaCheck() : impl_(std::make_unique<Impl>()) {}
SchemaCheck::~SchemaCheck() = default;
SchemaCheck::SchemaCheck(SchemaCheck&&) noexcept = default;

SchemaCheck SchemaCheck::load(const std::string& name, Strictness strictness) {
  const std::string path = std::string(kSchemaDir) + name + ".schema";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  SchemaCheck check;
  check.impl_->document = nlohmann::json::parse(in);
  patch_known_defects(name, check.impl_->document);
  if (strictness == Strictness::kStandardShape) forbid_extra_keys(check.impl_->document);
  valijson::SchemaParser parser(valijson::SchemaParser::kDraft7);
  valijson::adapters::NlohmannJsonAdapter adapter(check.impl_->document);
  parser.populateSchema(adapter, check.impl_->schema);
  return check;
}

std::string SchemaCheck::problems(const Json& message) const {
  const nlohmann::json plain = nlohmann::json::parse(message.dump());
  valijson::Validator validator;
  valijson::ValidationResults results;
  valijson::adapters::NlohmannJsonAdapter target(plain);
  if (validator.validate(impl_->schema, target, &results)) return "";
  std::ostringstream out;
  valijson::ValidationResults::Error error;
  while (results.popError(error)) {
    std::string where;
    for (const std::string& p : error.context) where += p;
    out << where << ": " << error.description << "\n";
  }
  return out.str();
}

}  // namespace rondo::vda5050::testing
