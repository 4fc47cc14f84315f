#include "ops/mapctl/state_history.h"

#include <gtest/gtest.h>

#include <fstream>

#include "aggregator/persistence/snapshot.h"
#include "aggregator/persistence/state_dir_lock.h"
#include "ops/mapctl/state_writer.h"
#include "tests/ops/mapctl/mapctl_fixture.h"

namespace fleetmap::ops::mapctl {
namespace {

using aggregator::MapPersistence;
using fleetmap::testing::ScratchFolder;
using testing::History;
using testing::StoreAt;
using testing::TinyHall;

TEST(StateHistoryTest, ReadsTheSnapshotThenTheNewerJournalRecords) {
  ScratchFolder folder;
  testing::WriteState(folder.path(), /*snapshot_after=*/2);
  auto h = ReadStateHistory(folder.path());
  ASSERT_TRUE(h.ok()) << h.status().ToString();
  EXPECT_TRUE(h->snapshot_found);
  EXPECT_EQ(h->snapshot_version, 2u);
  EXPECT_EQ(h->journal_records, 1);
  ASSERT_EQ(h->commits.size(), 3u);
  EXPECT_EQ(h->version(), 3u);
  EXPECT_EQ(h->commits[1].source.vehicle_id, "cts2");
  EXPECT_EQ(h->commits[2].changes, History()[2].changes);
}

TEST(StateHistoryTest, RebuildsEveryVersionAsTheStoreHadIt) {
  ScratchFolder folder;
  testing::WriteState(folder.path(), /*snapshot_after=*/1);
  auto h = ReadStateHistory(folder.path());
  ASSERT_TRUE(h.ok());
  for (uint64_t v = 0; v <= 3; ++v) {
    auto rebuilt = RebuildStore(TinyHall(), *h, v);
    ASSERT_TRUE(rebuilt.ok()) << rebuilt.status().ToString();
    EXPECT_EQ(rebuilt->version(), v);
    EXPECT_EQ(rebuilt->current_map().cells(), StoreAt(v).current_map().cells()) << v;
  }
  EXPECT_EQ(RebuildStore(TinyHall(), *h, 4).status().code(), core::StatusCode::kOutOfRange);
}

TEST(StateHistoryTest, RefusesAnotherStaticMap) {
  ScratchFolder folder;
  testing::WriteState(folder.path(), 3);
  auto h = ReadStateHistory(folder.path());
  ASSERT_TRUE(h.ok());
  core::OccupancyGrid other = TinyHall();
  other.SetState({3, 3}, core::CellState::kOccupied);
  EXPECT_EQ(RebuildStore(other, *h, 3).status().code(), core::StatusCode::kFailedPrecondition);
}

TEST(StateHistoryTest, NamesTheRecordOfACorruptJournal) {
  ScratchFolder folder;
  testing::WriteState(folder.path(), /*snapshot_after=*/0);
  const std::string journal = folder.File(MapPersistence::kJournalName);
  // Flip a payload byte of the first record: good records follow, so this is corruption,
  // not a torn tail.
  std::fstream f(journal, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(aggregator::kJournalHeaderBytes + aggregator::kJournalRecordHeaderBytes + 3);
  f.put('\x7f');
  f.close();
  auto h = ReadStateHistory(folder.path());
  ASSERT_FALSE(h.ok());
  EXPECT_EQ(h.status().code(), core::StatusCode::kDataLoss);
  EXPECT_NE(h.status().message().find(journal), std::string::npos) << h.status().message();
}

TEST(StateHistoryTest, AnEmptyFolderIsNotAStateFolder) {
  ScratchFolder folder;
  EXPECT_EQ(ReadStateHistory(folder.path()).status().code(), core::StatusCode::kNotFound);
}

TEST(StateWriterTest, RollbackThenExportIsTheMapAtThatVersion) {
  ScratchFolder folder;
  testing::WriteState(folder.path(), /*snapshot_after=*/2);
  auto before = ReadStateHistory(folder.path());
  ASSERT_TRUE(before.ok());
  auto at1 = RebuildStore(TinyHall(), *before, 1);
  ASSERT_TRUE(at1.ok());
  auto backup = ReplaceState(folder.path(), *at1, "rollback-test");
  ASSERT_TRUE(backup.ok()) << backup.status().ToString();

  auto after = ReadStateHistory(folder.path());
  ASSERT_TRUE(after.ok()) << after.status().ToString();
  EXPECT_EQ(after->version(), 1u);
  auto exported = RebuildStore(TinyHall(), *after, after->version());
  ASSERT_TRUE(exported.ok());
  EXPECT_EQ(exported->current_map().cells(), StoreAt(1).current_map().cells());
  // The old files are kept, and the backup is a state folder of its own at version 3.
  auto old = ReadStateHistory(*backup);
  ASSERT_TRUE(old.ok()) << old.status().ToString();
  EXPECT_EQ(old->version(), 3u);
  // The aggregator restarts from the rolled-back folder.
  aggregator::CurrentMapStore restarted(TinyHall(), {});
  auto persistence = MapPersistence::Open(folder.path(), restarted, {});
  ASSERT_TRUE(persistence.ok()) << persistence.status().ToString();
  EXPECT_EQ(restarted.version(), 1u);
  EXPECT_EQ(restarted.current_map().cells(), StoreAt(1).current_map().cells());
}

TEST(StateDirLockTest, AHeldFolderIsRefusedUntilItsHolderEnds) {
  ScratchFolder folder;
  {
    aggregator::CurrentMapStore store(TinyHall(), {});
    auto persistence = MapPersistence::Open(folder.path(), store, {});
    ASSERT_TRUE(persistence.ok());
    auto second = aggregator::StateDirLock::Acquire(folder.path());
    EXPECT_EQ(second.status().code(), core::StatusCode::kFailedPrecondition);
  }
  auto lock = aggregator::StateDirLock::Acquire(folder.path());
  ASSERT_TRUE(lock.ok()) << lock.status().ToString();
  EXPECT_TRUE(lock->held());
  aggregator::CurrentMapStore store(TinyHall(), {});
  EXPECT_EQ(MapPersistence::Open(folder.path(), store, {}).status().code(),
            core::StatusCode::kFailedPrecondition);
}

}  // namespace
}  // namespace fleetmap::ops::mapctl
