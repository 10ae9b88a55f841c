// The study store: a record reads back exactly as written (every double round-trips, lists and text included), a
// record made by another build is not reused, and absorbing a shard's store copies its records (what
// `beamid merge` does).
#include "study/run/store.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

#include "core/errors.h"
#include "io/files.h"

namespace beamid::study {
namespace {
namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("beamid-store-test-" + std::to_string(::getpid()) + "-" + name);
  fs::remove_all(p);
  return p;
}

TEST(Store, RecordsRoundTripEveryDouble) {
  Record r;
  // Values that a shorter format would round: 0.1, 1/3, the smallest normal and subnormal numbers, and the
  // non-finite values a failed fit stores.
  const std::vector<double> values = {
      0.1, 1.0 / 3.0, std::numeric_limits<double>::min(), std::numeric_limits<double>::denorm_min(), -2.5e300, 0.0};
  r.set("values", values);
  r.set("empty", std::vector<double>{});
  r.set("nan", std::numeric_limits<double>::quiet_NaN());
  r.set("inf", std::numeric_limits<double>::infinity());
  r.set("status", std::string("failed: a reason, with commas"));
  const Record back = Record::parse(r.serialise(), "test");
  EXPECT_EQ(back.numbers("values"), values);  // bit for bit
  EXPECT_TRUE(back.numbers("empty").empty());
  EXPECT_TRUE(std::isnan(back.number("nan")));
  EXPECT_EQ(back.number("inf"), std::numeric_limits<double>::infinity());
  EXPECT_EQ(back.text("status"), "failed: a reason, with commas");
  EXPECT_EQ(back.serialise(), r.serialise());
  EXPECT_THROW(back.text("absent"), InputError);
  EXPECT_THROW(Record::parse("no tab here\n", "f.rec"), InputError);
}

TEST(Store, ReusesOnlyRecordsOfTheSameBuild) {
  const fs::path dir = scratch("versions");
  Record r;
  r.set("x", 1.5);
  Store(dir.string(), "build-a").save("u1", r);
  EXPECT_TRUE(Store(dir.string(), "build-a").load("u1"));
  EXPECT_EQ(Store(dir.string(), "build-a").load("u1")->number("x"), 1.5);
  EXPECT_FALSE(Store(dir.string(), "build-b").load("u1")) << "another build's record must be recomputed";
  EXPECT_FALSE(Store(dir.string(), "build-a").load("u2"));
  fs::remove_all(dir);
}

TEST(Store, AbsorbCopiesAShardsRecords) {
  const fs::path a = scratch("shard-a"), b = scratch("shard-b"), merged = scratch("merged");
  Record r1, r2;
  r1.set("x", 1.0);
  r2.set("x", 2.0);
  Store(a.string(), "v").save("u1", r1);
  Store(b.string(), "v").save("u2", r2);
  const Store m(merged.string(), "v");
  EXPECT_EQ(m.absorb(a.string()).copied, 1);
  EXPECT_EQ(m.absorb(b.string()).copied, 1);
  EXPECT_EQ(m.load("u1")->number("x"), 1.0);
  EXPECT_EQ(m.load("u2")->number("x"), 2.0);
  EXPECT_THROW(m.absorb((a / "nope").string()), InputError);
  for (const auto& p : {a, b, merged}) fs::remove_all(p);
}

TEST(Store, AbsorbLeavesARecordOfAnotherBuildBehind) {
  // A shard record of another build replaced the output's valid one before the merge failed on it (the twenty-first
  // pass's P2): it is left behind and named, and the output's record is untouched.
  const fs::path shard = scratch("shard-old"), merged = scratch("merged-new");
  Record old_record, mine;
  old_record.set("x", 1.0);
  mine.set("x", 2.0);
  Store(shard.string(), "build-a").save("u1", old_record);
  const Store m(merged.string(), "build-b");
  m.save("u1", mine);
  const Store::Absorbed absorbed = m.absorb(shard.string());
  EXPECT_EQ(absorbed.copied, 0);
  ASSERT_EQ(absorbed.left_behind.size(), 1u);
  EXPECT_NE(absorbed.left_behind[0].find("a record of another build (code build-a, this is build-b)"),
            std::string::npos)
      << absorbed.left_behind[0];
  EXPECT_EQ(m.load("u1")->number("x"), 2.0);
  for (const auto& p : {shard, merged}) fs::remove_all(p);
}

TEST(Store, RecordsOfAnEarlierBuildWithoutCheckLinesAreRecomputedQuietly) {
  const fs::path dir = scratch("earlier");
  std::ostringstream log;
  const Store store(dir.string(), "new", &log);
  // As builds before the check line wrote them: sorted keys, "code" first for a truth record.
  io::write_file_atomic(dir / "truth.rec", "code\told\nstatus\tok\ny\t1 2 3\n");
  io::write_file_atomic(dir / "case.rec", "a4\tok\ncode\told\nstatus\tconverged\n");
  EXPECT_FALSE(store.load("truth"));
  EXPECT_FALSE(store.load("case"));
  EXPECT_TRUE(log.str().empty()) << log.str();
  EXPECT_FALSE(fs::exists(dir / "damaged"));
  fs::remove_all(dir);
}

TEST(Store, ARecordCutInsideItsCodeLineIsDamageNotAnotherBuilds) {
  // Cut to its first 20 bytes, "code\t55c6710cfb00-d", a record read as another build's and was recomputed without a
  // word (the fourth pass's Q393); an earlier build's whole record still is (the test above).
  const fs::path dir = scratch("first-line");
  std::ostringstream log;
  const Store store(dir.string(), "55c6710cfb00-dirty", &log);
  Record r;
  r.set("status", std::string("ok"));
  store.save("u", r);
  const std::string whole = io::read_file(dir / "u.rec", "record");
  ASSERT_EQ(whole.rfind("code\t", 0), 0u) << whole;
  io::write_file_atomic(dir / "u.rec", whole.substr(0, 20));
  EXPECT_FALSE(store.load("u"));
  EXPECT_TRUE(fs::exists(dir / "damaged" / "u.rec"));
  EXPECT_NE(log.str().find("u.rec"), std::string::npos) << log.str();
  fs::remove_all(dir);
}

TEST(Store, DamagedRecordsAreNamedMovedAsideAndRecomputed) {
  const fs::path dir = scratch("damage");
  std::ostringstream log;
  const Store store(dir.string(), "v", &log);
  Record r;
  r.set("status", std::string("ok"));
  r.set("cost", std::vector<double>{1, 2, 3, 4, 5, 6, 7, 8});
  const auto file = [&](const std::string& id) { return dir / (id + ".rec"); };
  const auto text_of = [&](const std::string& id) { return io::read_file(file(id), "record"); };
  for (const std::string id : {"cut", "flip", "garbage", "empty", "folder", "loop"}) store.save(id, r);
  const std::string whole = text_of("cut");
  io::write_file_atomic(file("cut"), whole.substr(0, whole.size() / 2));  // a record truncated in half
  std::string flipped = whole;
  flipped[whole.find("cost\t") + 5] = '9';  // one digit altered, the check line kept
  io::write_file_atomic(file("flip"), flipped);
  io::write_file_atomic(file("garbage"), std::string("\x7f\x01\xff\x00binary", 10));
  io::write_file_atomic(file("empty"), "");
  fs::remove(file("folder"));
  fs::create_directory(file("folder"));
  // A symbolic link to itself (the seventh pass's S15: exists() failed on it, so the unit was recomputed and its save
  // refused to replace the link, which stopped the study).
  fs::remove(file("loop"));
  fs::create_symlink(file("loop").filename(), file("loop"));
  for (const std::string id : {"cut", "flip", "garbage", "empty", "folder", "loop"}) {
    EXPECT_FALSE(store.load(id)) << id;
    EXPECT_EQ(fs::symlink_status(file(id)).type(), fs::file_type::not_found) << id << " must be moved aside";
    EXPECT_NE(fs::symlink_status(dir / "damaged" / (id + ".rec")).type(), fs::file_type::not_found) << id;
    EXPECT_NE(log.str().find(file(id).string()), std::string::npos) << "the log must name " << id;
  }
  for (const std::string id : {"cut", "loop"}) {
    store.save(id, r);  // recomputed: the new record is read back
    EXPECT_EQ(store.load(id)->numbers("cost").size(), 8u) << id;
  }
  fs::remove_all(dir);
}

// A record is bound to its unit: its id is inside the checked content, so an intact record under another unit's name
// (two records swapped, a file renamed) is named, moved aside and recomputed, and a shard's misnamed record is not
// merged; the caller's own check (the schema, record_schema.h) moves aside what it refuses in the same way.
TEST(Store, RecordsUnderAnotherUnitsNameOrRefusedByTheCallerAreMovedAside) {
  const fs::path dir = scratch("binding"), merged = scratch("binding-merged");
  std::ostringstream log;
  const Store store(dir.string(), "v", &log);
  Record r;
  r.set("x", 1.0);
  store.save("u1", r);
  EXPECT_EQ(store.load("u1")->text("unit"), "u1");
  fs::rename(dir / "u1.rec", dir / "u2.rec");
  EXPECT_FALSE(store.load("u2"));
  EXPECT_TRUE(fs::exists(dir / "damaged" / "u2.rec"));
  EXPECT_NE(log.str().find("it is the record of unit u1, not of u2 (renamed or swapped)"), std::string::npos)
      << log.str();
  store.save("u3", r);
  fs::copy_file(dir / "u3.rec", dir / "u4.rec");
  const Store::Absorbed absorbed = Store(merged.string(), "v").absorb(dir.string());
  EXPECT_EQ(absorbed.copied, 1);  // u3 only; u4, u3's record under another name, is left behind and named
  ASSERT_EQ(absorbed.left_behind.size(), 1u);
  EXPECT_NE(absorbed.left_behind[0].find("u4.rec: it is the record of unit u3, not of u4"), std::string::npos)
      << absorbed.left_behind[0];
  EXPECT_FALSE(fs::exists(merged / "u4.rec"));
  const auto refuse = [](const Record& record) { return record.has("y") ? "" : std::string("field 'y' is missing"); };
  EXPECT_FALSE(store.load("u3", refuse));
  EXPECT_TRUE(fs::exists(dir / "damaged" / "u3.rec"));
  EXPECT_NE(log.str().find("u3.rec: field 'y' is missing"), std::string::npos) << log.str();
  for (const auto& p : {dir, merged}) fs::remove_all(p);
}

}  // namespace
}  // namespace beamid::study
