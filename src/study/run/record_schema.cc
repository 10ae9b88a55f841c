#include "study/run/record_schema.h"

#include "core/errors.h"
#include "core/hash.h"
#include "io/text.h"

namespace beamid::study {
namespace {

void add_per_parameter(std::vector<FieldSpec>& fields, const std::string& prefix,
                       const std::vector<std::string>& estimate) {
  for (const auto& key : estimate) fields.push_back({prefix + key, FieldType::Number});
}

// A fit's outcome (record_fit / record_unrun_fit in execute.cc).
void add_fit(std::vector<FieldSpec>& fields, const std::vector<std::string>& estimate) {
  fields.push_back({"termination", FieldType::Text});
  fields.push_back({"cost", FieldType::Number});
  fields.push_back({"evaluations", FieldType::Number});
  add_per_parameter(fields, "estimate.", estimate);
}

}  // namespace

std::string inputs_hash(const Unit& unit) {
  return io::hex64(core::fnv1a64(unit.canonical + ";seed=" + std::to_string(unit.seed) + ";noise_seed=" +
                                 std::to_string(unit.noise_seed) + ";overlay=" + (unit.overlay ? "1" : "0")));
}

std::vector<FieldSpec> declared_fields(UnitKind kind, const std::vector<std::string>& estimate) {
  std::vector<FieldSpec> fields = {{"kind", FieldType::Text},
                                   {"inputs", FieldType::Text},
                                   {"status", FieldType::Text},
                                   {"wall_time_s", FieldType::Number}};
  switch (kind) {
    case UnitKind::Truth:
    case UnitKind::Slice:
    case UnitKind::Grid:
    case UnitKind::Multistart:
      break;  // what they hold beyond these depends on whether they ran (the tables read it only then)
    case UnitKind::Case:
      add_fit(fields, estimate);
      fields.push_back({"a4", FieldType::Text});
      add_per_parameter(fields, "standard_error.", estimate);
      add_per_parameter(fields, "relative_error.", estimate);
      break;
    case UnitKind::Start:
      add_fit(fields, estimate);
      fields.push_back({"frequency_offset", FieldType::Number});
      fields.push_back({"shrunk", FieldType::Number});
      add_per_parameter(fields, "start.", estimate);
      break;
    case UnitKind::Bound:
      fields.push_back({"noise_sd", FieldType::Number});
      add_per_parameter(fields, "relative_sd.", estimate);
      break;
    case UnitKind::Frequencies:
      fields.push_back({"exact_hz", FieldType::Numbers});
      fields.push_back({"galerkin_hz", FieldType::Numbers});
      break;
  }
  return fields;
}

std::string schema_violation(const Record& record, const Unit& unit, const std::vector<std::string>& estimate) {
  for (const FieldSpec& field : declared_fields(unit.kind, estimate)) {
    if (!record.has(field.name)) return "field '" + field.name + "' is missing";
    try {
      if (field.type == FieldType::Number) record.number(field.name);
      if (field.type == FieldType::Numbers) record.numbers(field.name);
    } catch (const InputError& e) {
      return e.what();
    }
  }
  if (record.text("kind") != unit_kind_name(unit.kind))
    return "it is a '" + record.text("kind") + "' record, where the unit is a '" + unit_kind_name(unit.kind) + "'";
  if (record.text("inputs") != inputs_hash(unit))
    return "it was made from other inputs than the unit's (another study seed, or without its overlay)";
  return "";
}

std::optional<Record> load_unit(const Store& store, const Unit& unit, const std::vector<std::string>& estimate) {
  return store.load(unit.id, [&](const Record& r) { return schema_violation(r, unit, estimate); });
}

}  // namespace beamid::study
