#include <gtest/gtest.h>

#include <filesystem>

#include "aggregator/aggregator.h"
#include "aggregator/persistence/map_persistence.h"
#include "aggregator/persistence/snapshot.h"
#include "tests/aggregator/test_files.h"
#include "tests/aggregator/test_hall.h"

namespace fleetmap::aggregator {
namespace {

using testing::ReadAll;
using testing::WriteAll;

// Temporary maps of the hall with a pallet in it, at 10 s intervals, with anchor errors.
class PersistenceTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const core::OccupancyGrid world = testing::HallMap(0.0, {{{6.0, 7.0}, {1.2, 0.8}}});
    for (int i = 0; i < 4; ++i) {
      testing::TempMapSpec spec;
      spec.start = {3.013 + 0.7 * i, 5.027, 0.0};
      spec.anchor_error = {0.1 * (i % 3) - 0.1, 0.07 * i - 0.1, (i - 1.5) * M_PI / 180};
      spec.sequence = i + 1;
      spec.start_s = 20.0 * i;
      spec.end_s = 20.0 * i + 10.0;
      spec.seed = 11 + i;
      maps_->push_back(testing::BuildTempMap(world, spec));
    }
  }
  static void TearDownTestSuite() { maps_->clear(); }

  AggregatorOptions Options(int snapshot_every = 100) {
    AggregatorOptions o;
    o.persistence.snapshot_every_merges = snapshot_every;
    return o;
  }
  Aggregator Open(const AggregatorOptions& o, RestoreReport* report = nullptr) {
    auto a = Aggregator::Open(testing::HallMap(), o, folder_.path(), report);
    EXPECT_TRUE(a.ok()) << a.status().ToString();
    return std::move(a).value();
  }
  static void Feed(Aggregator& a, size_t from, size_t to) {
    for (size_t i = from; i < to; ++i) {
      const auto r = a.Submit((*maps_)[i], (*maps_)[i].end_s);
      ASSERT_TRUE(r.ok()) << r.status().ToString();
      ASSERT_TRUE(r->accepted) << i << ": " << r->reason_text;
    }
  }
  static void ExpectSame(const Aggregator& a, const Aggregator& b) {
    EXPECT_EQ(a.store().version(), b.store().version());
    EXPECT_EQ(a.store().current_map().cells(), b.store().current_map().cells());
    EXPECT_EQ(a.store().semi_static(), b.store().semi_static());
    EXPECT_EQ(a.store().candidate_mask(), b.store().candidate_mask());
    EXPECT_EQ(a.store().provenance().num_changes(), b.store().provenance().num_changes());
    EXPECT_EQ(EncodeSnapshot(a.store()), EncodeSnapshot(b.store()));
  }

  static std::vector<core::TempMap>* maps_;
  fleetmap::testing::ScratchFolder folder_;
  std::string journal_ = folder_.File(MapPersistence::kJournalName);
  std::string snapshot_ = folder_.File(MapPersistence::kSnapshotName);
};
std::vector<core::TempMap>* PersistenceTest::maps_ = new std::vector<core::TempMap>();

TEST_F(PersistenceTest, RestartFromTheJournalGivesTheSameMapAndVersion) {
  {
    Aggregator a = Open(Options());
    Feed(a, 0, 3);
    ASSERT_GT(std::count(a.store().semi_static().begin(), a.store().semi_static().end(), 1), 20);
  }
  RestoreReport report;
  Aggregator restarted = Open(Options(), &report);
  EXPECT_FALSE(report.snapshot_found);
  EXPECT_EQ(report.journal_records, 3);
  EXPECT_FALSE(report.torn_tail_dropped);
  auto reference = Aggregator::Create(testing::HallMap(), Options());
  Feed(*reference, 0, 3);
  ExpectSame(restarted, *reference);
  // And it goes on exactly as one that never stopped.
  Feed(restarted, 3, 4);
  Feed(*reference, 3, 4);
  ExpectSame(restarted, *reference);
}

TEST_F(PersistenceTest, CandidatesSeenFreeAreDroppedInAJournaledVersionOfTheirOwn) {
  const auto drop_three = [](Aggregator& a) {
    std::vector<int64_t> cells = CandidateCells(a.store().candidates());
    EXPECT_GE(cells.size(), 3u);
    cells.resize(3);
    const std::vector<int64_t> asked = {cells[2], cells[0], cells[1], 0};  // 0: no candidate
    const uint64_t version = a.store().version();
    // A pass before the sighting's end says nothing about it.
    auto early = a.DropCandidatesSeenFree("v1", {asked, 5.0, 6.0}, 30.0);
    EXPECT_TRUE(early.ok() && early->empty());
    EXPECT_EQ(a.store().version(), version);
    auto dropped = a.DropCandidatesSeenFree("v1", {asked, 12.0, 13.0}, 30.0);
    EXPECT_TRUE(dropped.ok());
    EXPECT_EQ(*dropped, cells);  // the three candidates, ascending
    EXPECT_EQ(a.store().version(), version + 1);
    for (int64_t c : cells) EXPECT_EQ(a.store().candidates().count(c), 0u) << c;
  };
  {
    Aggregator a = Open(Options());
    Feed(a, 0, 1);  // seen once: candidates
    drop_three(a);
  }
  RestoreReport report;
  Aggregator restarted = Open(Options(), &report);
  EXPECT_EQ(report.journal_records, 2);
  auto reference = Aggregator::Create(testing::HallMap(), Options());
  Feed(*reference, 0, 1);
  drop_three(*reference);
  ExpectSame(restarted, *reference);
}

TEST_F(PersistenceTest, TornLastRecordIsDroppedAndTheMapIsTheVersionBefore) {
  std::vector<char> two;
  {
    Aggregator a = Open(Options());
    Feed(a, 0, 2);
    two = ReadAll(journal_);
    Feed(a, 2, 3);
  }
  // The last merge was being written when power went (never committed, never acknowledged).
  WriteAll(journal_, testing::CrashedWhileAppending(two, ReadAll(journal_), 7));
  RestoreReport report;
  Aggregator restarted = Open(Options(), &report);
  EXPECT_TRUE(report.torn_tail_dropped);
  EXPECT_FALSE(report.torn_detail.empty());
  auto reference = Aggregator::Create(testing::HallMap(), Options());
  Feed(*reference, 0, 2);
  ExpectSame(restarted, *reference);
  Feed(restarted, 2, 3);  // the vehicle sends the unacknowledged map again
  Feed(*reference, 2, 3);
  ExpectSame(restarted, *reference);
  EXPECT_FALSE(ReadJournal(journal_, 1 << 30)->torn_tail);
}

// Damage to what the journal committed (acknowledged merges): the aggregator refuses to
// start, names the record and byte, and leaves the file as it is.
TEST_F(PersistenceTest, ADamagedJournalRefusesToStartAndIsLeftAsItIs) {
  {
    Aggregator a = Open(Options());
    Feed(a, 0, 3);
  }
  const std::vector<char> good = ReadAll(journal_);
  std::vector<char> cut(good.begin(), good.begin() + good.size() / 2);  // mid-file
  std::vector<char> zeroed = good;
  for (size_t i = kJournalHeaderBytes; i < zeroed.size(); ++i) zeroed[i] = 0;  // same length
  std::vector<char> flipped = good;
  flipped[flipped.size() - 3] ^= 0x10;  // in the last, full-length record
  for (const auto& damaged : {cut, zeroed, flipped}) {
    WriteAll(journal_, damaged);
    auto restarted = Aggregator::Open(testing::HallMap(), Options(), folder_.path());
    ASSERT_FALSE(restarted.ok());
    EXPECT_EQ(restarted.status().code(), core::StatusCode::kDataLoss);
    EXPECT_NE(restarted.status().message().find("record"), std::string::npos);
    EXPECT_NE(restarted.status().message().find("byte"), std::string::npos);
    EXPECT_EQ(ReadAll(journal_), damaged) << "the journal was modified";
  }
}

TEST_F(PersistenceTest, RestartFromSnapshotAndJournal) {
  {
    Aggregator a = Open(Options(2));
    Feed(a, 0, 3);
  }  // a snapshot after 2, one record after
  RestoreReport report;
  Aggregator restarted = Open(Options(2), &report);
  EXPECT_TRUE(report.snapshot_found);
  EXPECT_EQ(report.snapshot_version, 2u);
  EXPECT_EQ(report.journal_records, 1);
  auto reference = Aggregator::Create(testing::HallMap(), Options());
  Feed(*reference, 0, 3);
  ExpectSame(restarted, *reference);
}

TEST_F(PersistenceTest, CrashBetweenSnapshotAndJournalResetSkipsWhatTheSnapshotHolds) {
  {
    Aggregator a = Open(Options());
    Feed(a, 0, 3);
    ASSERT_TRUE(WriteSnapshot(a.store(), snapshot_).ok());  // the journal is not reset
  }
  RestoreReport report;
  Aggregator restarted = Open(Options(), &report);
  EXPECT_EQ(report.snapshot_version, 3u);
  EXPECT_EQ(report.journal_skipped, 3);
  EXPECT_EQ(restarted.store().version(), 3u);
}

TEST_F(PersistenceTest, ForeignOrCorruptSnapshotIsRefused) {
  {
    Aggregator a = Open(Options(1));
    Feed(a, 0, 2);
  }
  auto other = Aggregator::Open(testing::HallMap(0.2), Options(), folder_.path());
  EXPECT_EQ(other.status().code(), core::StatusCode::kFailedPrecondition);
  std::vector<char> bytes = ReadAll(snapshot_);
  bytes[bytes.size() / 2] ^= 0x10;
  WriteAll(snapshot_, bytes);
  EXPECT_EQ(Aggregator::Open(testing::HallMap(), Options(), folder_.path()).status().code(),
            core::StatusCode::kDataLoss);
}

TEST_F(PersistenceTest, FullDiskAcknowledgesNothing) {
  Aggregator a = Open(Options());
  Feed(a, 0, 1);
  const std::vector<float> before = a.store().current_map().cells();
  const uintmax_t journal_size = std::filesystem::file_size(journal_);
  {
    testing::FileSizeLimit full(journal_size + 10);
    const auto r = a.Submit((*maps_)[1], (*maps_)[1].end_s);
    EXPECT_EQ(r.status().code(), core::StatusCode::kIoError);
  }
  EXPECT_EQ(a.store().version(), 1u);
  EXPECT_EQ(a.store().current_map().cells(), before);
  EXPECT_EQ(std::filesystem::file_size(journal_), journal_size);
  Feed(a, 1, 2);  // space again: the vehicle's resend is merged
  EXPECT_EQ(a.store().version(), 2u);
}

TEST_F(PersistenceTest, SameInputsGiveByteIdenticalMapsAndJournals) {
  fleetmap::testing::ScratchFolder other;
  {
    Aggregator a = Open(Options());
    auto b = Aggregator::Open(testing::HallMap(), Options(), other.path());
    ASSERT_TRUE(b.ok());
    Feed(a, 0, 4);
    Feed(*b, 0, 4);
    ExpectSame(a, *b);
  }
  EXPECT_EQ(ReadAll(journal_), ReadAll(other.File(MapPersistence::kJournalName)));
}

}  // namespace
}  // namespace fleetmap::aggregator
