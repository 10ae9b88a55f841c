// The store's declared schema (record_schema.h) against the writer: a unit of every kind whose truth failed still
// writes every declared field (its "not run" values), and the reader refuses a record that lacks one, has one of the
// wrong type, is of another kind or was made from other inputs (another study seed). (Records of units that ran are
// checked in study_runner_test.cc.)
#include "study/run/record_schema.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <sstream>

#include "study/run/execute.h"

namespace beamid::study {
namespace {

TEST(RecordSchema, AUnitOfEveryKindWritesItsDeclaredFieldsEvenWhenItCannotRun) {
  StudySpec spec;
  spec.truth.parameters = model::preset("banks-aluminium");
  spec.fit.estimate = {"EI", "rho"};
  Record truth;
  truth.set("status", std::string("failed: a test truth"));
  for (UnitKind kind :
       {UnitKind::Case, UnitKind::Slice, UnitKind::Grid, UnitKind::Multistart, UnitKind::Start, UnitKind::Bound}) {
    Unit u;
    u.kind = kind;
    u.elements = 4;
    u.samples = 64;
    const Record r = run_unit(spec, u, truth);
    EXPECT_EQ(r.text("status").rfind("failed", 0), 0u) << unit_kind_name(kind);
    EXPECT_EQ(schema_violation(r, u, spec.fit.estimate), "") << unit_kind_name(kind);
  }
}

TEST(RecordSchema, ARecordWithoutAFieldOfTheWrongTypeOrKindIsRefused) {
  Unit u;
  u.kind = UnitKind::Bound;
  const std::vector<std::string> estimate = {"EI"};
  Record r;
  r.set("kind", std::string("bound"));
  r.set("inputs", inputs_hash(u));
  r.set("status", std::string("ok"));
  r.set("wall_time_s", 0.5);
  r.set("noise_sd", 1e-3);
  r.set("relative_sd.EI", 0.01);
  EXPECT_EQ(schema_violation(r, u, estimate), "");
  EXPECT_EQ(schema_violation(r, u, {"EI", "rho"}), "field 'relative_sd.rho' is missing");
  Record wrong_type = r;
  wrong_type.set("noise_sd", std::string("small"));
  EXPECT_NE(schema_violation(wrong_type, u, estimate).find("'noise_sd' = 'small': must be a number"),
            std::string::npos);
  Record wrong_kind = r;
  wrong_kind.set("kind", std::string("case"));
  EXPECT_EQ(schema_violation(wrong_kind, u, estimate), "it is a 'case' record, where the unit is a 'bound'");
  Unit reseeded = u;  // the same unit id in a study with another seed
  reseeded.seed = u.seed + 1;
  EXPECT_NE(schema_violation(r, reseeded, estimate).find("made from other inputs"), std::string::npos);
}

// The store_record fuzzer's seed (tests/fuzz/corpus/store_record/case.rec) is a valid, checked record of a case that
// follows the schema, so that the fuzzer starts from records that reach every check.
TEST(RecordSchema, TheFuzzSeedIsAValidCaseRecord) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("beamid-schema-seed-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(fs::path(BEAMID_SOURCE_DIR) / "tests/fuzz/corpus/store_record/case.rec", dir / "0123456789abcdef.rec");
  std::ostringstream log;
  const Store store(dir.string(), "fuzz", &log);
  Unit u;
  u.kind = UnitKind::Case;
  u.id = "0123456789abcdef";
  EXPECT_TRUE(load_unit(store, u, {"EI", "rho"})) << log.str();
  fs::remove_all(dir);
}

}  // namespace
}  // namespace beamid::study
