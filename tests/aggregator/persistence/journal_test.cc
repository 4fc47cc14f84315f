#include "aggregator/persistence/journal.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "tests/aggregator/test_files.h"

namespace fleetmap::aggregator {
namespace {

using testing::CrashedWhileAppending;
using testing::ReadAll;
using testing::WriteAll;

std::vector<uint8_t> Payload(int i) { return std::vector<uint8_t>(10 + i, uint8_t(i)); }

class JournalTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto writer = JournalWriter::Open(path_, JournalContents{});
    ASSERT_TRUE(writer.ok()) << writer.status().ToString();
    for (int i = 0; i < 2; ++i) ASSERT_TRUE(writer->Append(Payload(i)).ok());
    two_ = ReadAll(path_);
    ASSERT_TRUE(writer->Append(Payload(2)).ok());
    good_ = ReadAll(path_);
  }
  JournalWriter OpenFound() {
    auto writer = JournalWriter::Open(path_, Read());
    EXPECT_TRUE(writer.ok()) << writer.status().ToString();
    return std::move(writer).value();
  }
  // Damage to what was committed: DataLoss naming the record and byte.
  void ExpectDamaged(const std::vector<char>& bytes, const std::string& record) {
    WriteAll(path_, bytes);
    auto c = ReadJournal(path_, 1 << 20);
    ASSERT_FALSE(c.ok());
    EXPECT_EQ(c.status().code(), core::StatusCode::kDataLoss);
    EXPECT_NE(c.status().message().find(record), std::string::npos) << c.status().message();
    EXPECT_NE(c.status().message().find("at byte"), std::string::npos) << c.status().message();
  }
  JournalContents Read() {
    auto c = ReadJournal(path_, 1 << 20);
    EXPECT_TRUE(c.ok()) << c.status().ToString();
    return c.ok() ? *c : JournalContents{};
  }
  // After a torn tail: the first two records survive, and appending continues cleanly.
  void ExpectTwoThenRecovers() {
    const JournalContents c = Read();
    EXPECT_TRUE(c.torn_tail);
    ASSERT_EQ(c.records.size(), 2u);
    EXPECT_EQ(c.records[1], Payload(1));
    auto writer = JournalWriter::Open(path_, c);
    ASSERT_TRUE(writer.ok());
    ASSERT_TRUE(writer->Append(Payload(7)).ok());
    const JournalContents after = Read();
    EXPECT_FALSE(after.torn_tail);
    ASSERT_EQ(after.records.size(), 3u);
    EXPECT_EQ(after.records[2], Payload(7));
  }

  fleetmap::testing::ScratchFolder folder_;
  std::string path_ = folder_.File("journal.fmj");
  std::vector<char> two_;   // after two records
  std::vector<char> good_;  // after three
};

TEST_F(JournalTest, ReadsBackWhatWasAppended) {
  const JournalContents c = Read();
  EXPECT_FALSE(c.torn_tail);
  ASSERT_EQ(c.records.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(c.records[i], Payload(i));
  EXPECT_EQ(c.valid_bytes, good_.size());
}

TEST_F(JournalTest, HalfWrittenLastRecordIsDropped) {
  WriteAll(path_, CrashedWhileAppending(two_, good_, 5));
  ExpectTwoThenRecovers();
}

TEST_F(JournalTest, ShortLastRecordHeaderIsDropped) {
  const size_t record = kJournalRecordHeaderBytes + Payload(2).size();
  WriteAll(path_, CrashedWhileAppending(two_, good_, record - 7));
  ExpectTwoThenRecovers();
}

TEST_F(JournalTest, AWholeRecordNeverCommittedIsDropped) {
  std::vector<char> bad = CrashedWhileAppending(two_, good_, 0);
  bad[bad.size() - 3] ^= 0x40;  // its CRC need not even hold: it was never committed
  WriteAll(path_, bad);
  ExpectTwoThenRecovers();
}

TEST_F(JournalTest, ZerosAfterTheLastRecordAreDropped) {
  std::vector<char> padded = good_;
  padded.resize(good_.size() + 30, 0);
  WriteAll(path_, padded);
  const JournalContents c = Read();
  EXPECT_TRUE(c.torn_tail);
  EXPECT_EQ(c.records.size(), 3u);
}

TEST_F(JournalTest, ACommittedRecordCutShortIsDamage) {
  ExpectDamaged(std::vector<char>(good_.begin(), good_.end() - 5), "record 3 of 3");
  ExpectDamaged(std::vector<char>(good_.begin(), good_.begin() + two_.size() - 4), "record 2 of 3");
}

TEST_F(JournalTest, CommittedRecordsZeroedAtTheSameLengthAreDamage) {
  std::vector<char> zeroed = good_;
  for (size_t i = kJournalHeaderBytes; i < zeroed.size(); ++i) zeroed[i] = 0;
  ExpectDamaged(zeroed, "record 1 of 3");
}

TEST_F(JournalTest, ABitFlippedInTheLastCommittedRecordIsDamage) {
  std::vector<char> bad = good_;
  bad[bad.size() - 3] ^= 0x40;
  ExpectDamaged(bad, "record 3 of 3");
  bad = good_;
  bad[9] ^= 0x01;  // the commit block itself
  ExpectDamaged(bad, "commit block");
}

// For an operator's recovery: the intact records before the damage, and how many were
// committed.
TEST_F(JournalTest, SalvageKeepsTheIntactRecordsBeforeTheDamage) {
  std::vector<char> bad = good_;
  bad[two_.size() - 3] ^= 0x40;  // inside record 2
  WriteAll(path_, bad);
  auto s = SalvageJournal(path_, 1 << 20);
  ASSERT_TRUE(s.ok()) << s.status().ToString();
  ASSERT_EQ(s->records.size(), 1u);
  EXPECT_EQ(s->records[0], Payload(0));
  EXPECT_EQ(s->committed_records, 3);
  EXPECT_NE(s->damage.find("record 2 at byte"), std::string::npos) << s->damage;
  EXPECT_EQ(ReadAll(path_), bad);  // read only

  WriteAll(path_, std::vector<char>(good_.begin(), good_.end() - 5));
  s = SalvageJournal(path_, 1 << 20);
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->records.size(), 2u);
  EXPECT_NE(s->damage.find("record 3"), std::string::npos) << s->damage;

  bad = good_;
  bad[9] ^= 0x01;  // the commit block: the records are read on, their number is unknown
  WriteAll(path_, bad);
  s = SalvageJournal(path_, 1 << 20);
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->records.size(), 3u);
  EXPECT_EQ(s->committed_records, -1);
  EXPECT_NE(s->damage.find("commit block"), std::string::npos) << s->damage;

  WriteAll(path_, CrashedWhileAppending(two_, good_, 0));  // a record never committed
  s = SalvageJournal(path_, 1 << 20);
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->records.size(), 2u);
  EXPECT_EQ(s->committed_records, 2);
  EXPECT_TRUE(s->damage.empty()) << s->damage;

  WriteAll(path_, std::vector<char>(40, 'x'));
  s = SalvageJournal(path_, 1 << 20);
  ASSERT_TRUE(s.ok());
  EXPECT_TRUE(s->records.empty());
  EXPECT_EQ(s->damage, "no journal header");
}

TEST_F(JournalTest, AFormatOneJournalIsReadAndRewrittenAsFormatTwo) {
  // Format 1: the same records after "FMJ1" and version 1, without a commit block.
  std::vector<char> v1 = good_;
  v1.erase(v1.begin() + kJournalV1HeaderBytes, v1.begin() + kJournalHeaderBytes);
  v1[4] = 1;
  WriteAll(path_, v1);
  JournalContents c = Read();
  EXPECT_EQ(c.format_version, 1u);
  ASSERT_EQ(c.records.size(), 3u);
  JournalWriter writer = OpenFound();
  EXPECT_EQ(ReadAll(path_), good_);  // rewritten: the same records, committed
  ASSERT_TRUE(writer.Append(Payload(3)).ok());
  c = Read();
  EXPECT_EQ(c.format_version, kJournalFormatVersion);
  ASSERT_EQ(c.records.size(), 4u);
  EXPECT_EQ(c.records[3], Payload(3));
}

TEST_F(JournalTest, CorruptionBeforeTheEndIsAnError) {
  std::vector<char> bad = good_;
  bad[kJournalHeaderBytes + kJournalRecordHeaderBytes + 2] ^= 0x01;  // first record's payload
  WriteAll(path_, bad);
  EXPECT_EQ(ReadJournal(path_, 1 << 20).status().code(), core::StatusCode::kDataLoss);
  WriteAll(path_, {'n', 'o', 't', ' ', 'o', 'u', 'r', 's', '!'});
  EXPECT_EQ(ReadJournal(path_, 1 << 20).status().code(), core::StatusCode::kDataLoss);
  EXPECT_EQ(ReadJournal(folder_.File("none"), 1 << 20).status().code(),
            core::StatusCode::kNotFound);
}

TEST_F(JournalTest, FullDiskFailsTheAppendAndLeavesNoPartialRecord) {
  auto writer = JournalWriter::Open(path_, Read());
  ASSERT_TRUE(writer.ok());
  {
    testing::FileSizeLimit full(good_.size() + 6);  // room for half a record header
    const core::Status s = writer->Append(Payload(5));
    EXPECT_EQ(s.code(), core::StatusCode::kIoError);
    EXPECT_NE(s.message().find("journal write failed"), std::string::npos) << s.ToString();
  }
  EXPECT_EQ(std::filesystem::file_size(path_), good_.size());
  EXPECT_EQ(Read().records.size(), 3u);
  EXPECT_FALSE(Read().torn_tail);
  ASSERT_TRUE(writer->Append(Payload(5)).ok());  // room again: appending goes on
  EXPECT_EQ(Read().records.size(), 4u);
}

TEST_F(JournalTest, ResetEmptiesIt) {
  auto writer = JournalWriter::Open(path_, Read());
  ASSERT_TRUE(writer.ok());
  ASSERT_TRUE(writer->Reset().ok());
  EXPECT_TRUE(Read().records.empty());
  EXPECT_EQ(writer->size_bytes(), kJournalHeaderBytes);
}

}  // namespace
}  // namespace fleetmap::aggregator
