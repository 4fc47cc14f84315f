#include "ops/mapctl/state_recovery.h"

#include <gtest/gtest.h>

#include <fstream>

#include "aggregator/persistence/map_persistence.h"
#include "ops/mapctl/state_writer.h"
#include "tests/ops/mapctl/mapctl_fixture.h"

namespace fleetmap::ops::mapctl {
namespace {

using aggregator::MapPersistence;
using aggregator::testing::ReadAll;
using aggregator::testing::WriteAll;
using fleetmap::testing::ScratchFolder;
using testing::StoreAt;
using testing::TinyHall;

void FlipByte(const std::string& path, size_t at) {
  std::vector<char> bytes = ReadAll(path);
  ASSERT_LT(at, bytes.size());
  bytes[at] ^= 0x40;
  WriteAll(path, bytes);
}

// The journal's second record (version 2 of 3) damaged: versions 1 is recovered, 2 and 3
// are reported lost; written as the new state, the aggregator opens the folder at version 1
// and the damaged journal is kept in the backup.
TEST(StateRecoveryTest, KeepsTheMergesBeforeTheDamageAndCountsTheLostOnes) {
  ScratchFolder folder;
  testing::WriteState(folder.path(), /*snapshot_after=*/0);
  const std::string journal = folder.File(MapPersistence::kJournalName);
  const std::vector<char> damaged_bytes = [&] {
    auto salvage = aggregator::SalvageJournal(journal, 1 << 20);
    EXPECT_TRUE(salvage.ok());
    // The first byte of record 2's payload: header, record 1, record 2's header.
    const size_t at = aggregator::kJournalHeaderBytes + aggregator::kJournalRecordHeaderBytes +
                      salvage->records[0].size() + aggregator::kJournalRecordHeaderBytes;
    FlipByte(journal, at);
    return ReadAll(journal);
  }();
  EXPECT_FALSE(ReadStateHistory(folder.path()).ok());  // what the aggregator refuses

  auto r = ReadRecoverableHistory(folder.path());
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_TRUE(r->damaged());
  EXPECT_EQ(r->history.version(), 1u);
  EXPECT_EQ(r->journal_read, 1);
  EXPECT_EQ(r->journal_committed, 3);
  EXPECT_EQ(r->versions_lost, 2);
  EXPECT_NE(r->journal_damage.find("record 2"), std::string::npos) << r->journal_damage;
  EXPECT_EQ(ReadAll(journal), damaged_bytes);  // reading changes nothing

  auto store = RebuildStore(TinyHall(), r->history, r->history.version());
  ASSERT_TRUE(store.ok());
  auto backup = ReplaceState(folder.path(), *store, "recover-test");
  ASSERT_TRUE(backup.ok()) << backup.status().ToString();
  EXPECT_EQ(ReadAll(*backup + "/" + MapPersistence::kJournalName), damaged_bytes);

  aggregator::CurrentMapStore reopened(TinyHall(), {});
  auto persistence = MapPersistence::Open(folder.path(), reopened, {});
  ASSERT_TRUE(persistence.ok()) << persistence.status().ToString();
  EXPECT_EQ(reopened.version(), 1u);
  EXPECT_EQ(reopened.current_map().cells(), StoreAt(1).current_map().cells());
  auto after = ReadRecoverableHistory(folder.path());
  ASSERT_TRUE(after.ok());
  EXPECT_FALSE(after->damaged());
}

// A damaged snapshot takes its merges with it (the journal's records build on them): the
// static map is what is left, and how much is lost is unknown.
TEST(StateRecoveryTest, ADamagedSnapshotLeavesTheStaticMap) {
  ScratchFolder folder;
  testing::WriteState(folder.path(), /*snapshot_after=*/2);
  FlipByte(folder.File(MapPersistence::kSnapshotName), 20);
  auto r = ReadRecoverableHistory(folder.path());
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_FALSE(r->snapshot_damage.empty());
  EXPECT_EQ(r->history.version(), 0u);
  EXPECT_EQ(r->versions_lost, -1);
  EXPECT_NE(r->journal_damage.find("does not follow version 0"), std::string::npos)
      << r->journal_damage;
}

TEST(StateRecoveryTest, AnIntactFolderHasNothingToRecover) {
  ScratchFolder folder;
  testing::WriteState(folder.path(), /*snapshot_after=*/1);
  auto r = ReadRecoverableHistory(folder.path());
  ASSERT_TRUE(r.ok());
  EXPECT_FALSE(r->damaged());
  EXPECT_EQ(r->history.version(), 3u);
  EXPECT_EQ(r->versions_lost, 0);
  ScratchFolder empty;
  EXPECT_EQ(ReadRecoverableHistory(empty.path()).status().code(), core::StatusCode::kNotFound);
}

}  // namespace
}  // namespace fleetmap::ops::mapctl
