// The declared schema of the study store's records: for each unit kind, the fields that every record of that kind
// carries, whether its unit succeeded or failed, with their types. The writer (execute.cc) sets them first with "not
// run" values (tests/study/record_schema_test.cc runs every kind, succeeding and failing, against this table) and the
// reader checks a stored record against it before using it (runner.cc, results.cc), so that a record that does not
// follow it is moved aside and recomputed like any damaged record, never half read by a table.
#pragma once

#include <string>
#include <vector>

#include "study/plan/plan.h"
#include "study/run/store.h"

namespace beamid::study {

enum class FieldType { Text, Number, Numbers };

struct FieldSpec {
  std::string name;
  FieldType type;
};

// A hash of everything that made a unit's record beyond its id (the canonical text the id hashes): its seed and its
// record's noise seed, which derive from the study's seed, and whether it computes an overlay. Stored in the record
// ("inputs") and compared on reading, so that a record made with another study seed, say, is recomputed.
std::string inputs_hash(const Unit& unit);

// The fields every record of `kind` carries, for a study that estimates `estimate` (the per-parameter fields
// "estimate.EI", "relative_error.EI", ... are listed for each key). Includes "kind" (the unit kind's name), "inputs"
// (inputs_hash) and "status"; the store adds "unit" and "code" itself.
std::vector<FieldSpec> declared_fields(UnitKind kind, const std::vector<std::string>& estimate);

// Why `record` does not follow the schema of `unit` (the first field missing, of the wrong type, a kind that is not
// the unit's, or other inputs), or "" when it does.
std::string schema_violation(const Record& record, const Unit& unit, const std::vector<std::string>& estimate);

// The stored record of `unit`, checked against its schema (a record that does not follow it is moved aside).
std::optional<Record> load_unit(const Store& store, const Unit& unit, const std::vector<std::string>& estimate);

}  // namespace beamid::study
