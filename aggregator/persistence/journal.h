// The append-only journal of accepted merges. Every record is written and fsynced, then
// committed (the header's commit block names it, fsynced again), before the merge is
// acknowledged; on start the journal is read back and replayed after the snapshot.
// File layout (little-endian):
//
//   header  "FMJ1", u32 format version (kJournalFormatVersion), then the commit block:
//           u64 committed bytes (the file's length up to the end of the last committed
//           record), u32 committed records, u32 CRC-32 of those 12 bytes
//   record  u32 magic "FMJR", u32 payload length, u32 CRC-32 of the payload, the payload
//
// A crash can leave one record written but not committed, whole or in part (a torn tail):
// it was never acknowledged, is dropped and cut off before the next append. Every committed
// record must be there and intact: a journal cut short, zeroed or with a flipped bit anywhere
// in what it committed is damage, and reading fails with DataLoss naming the record and byte
// (the file is left as it is: acknowledged merges are in it, or were). Format 1 journals
// (no commit block; written before) are read by the old rule, where only a bad record before
// good data could be told from a torn tail, and rewritten as format 2 on the next open.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"

namespace fleetmap::aggregator {

constexpr uint32_t kJournalFormatVersion = 2;
constexpr size_t kJournalHeaderBytes = 24;   // format 2: magic, version, commit block
constexpr size_t kJournalV1HeaderBytes = 8;  // format 1: magic, version
constexpr size_t kJournalRecordHeaderBytes = 12;
constexpr uint32_t kMaxJournalRecordBytes = 64u << 20;

struct JournalContents {
  std::vector<std::vector<uint8_t>> records;  // payloads, in order
  uint64_t valid_bytes = 0;  // the file length up to the end of the last good record
  bool torn_tail = false;    // a record never committed was found and dropped
  std::string torn_detail;   // what the tail looked like, for the log
  uint32_t format_version = kJournalFormatVersion;
};

// NotFound when the file does not exist; DataLoss for corruption; OutOfRange over max_bytes.
core::Result<JournalContents> ReadJournal(const std::string& path, int64_t max_bytes);

// What can still be read from a damaged journal, for an operator's recovery: the records
// from the first up to the first one that is not intact (or up to the last committed one).
struct JournalSalvage {
  std::vector<std::vector<uint8_t>> records;  // intact payloads, in order
  int64_t committed_records = -1;             // as the commit block says; -1 when it cannot be read
  std::string damage;  // where reading stopped, and why; empty: nothing damaged
};
// NotFound when the file does not exist; OutOfRange over max_bytes; never DataLoss.
core::Result<JournalSalvage> SalvageJournal(const std::string& path, int64_t max_bytes);

class JournalWriter {
 public:
  // Opens the journal ReadJournal found (`found`), cut to its good records so that a torn
  // tail is gone before the next record, or creates one when `found` is empty (no file). A
  // format 1 journal is rewritten as format 2 first (a new file renamed over it). IoError
  // naming the path on failure.
  static core::Result<JournalWriter> Open(const std::string& path, const JournalContents& found);

  JournalWriter(JournalWriter&& other) noexcept;
  JournalWriter& operator=(JournalWriter&& other) noexcept;
  JournalWriter(const JournalWriter&) = delete;
  JournalWriter& operator=(const JournalWriter&) = delete;
  ~JournalWriter();

  // Writes one record and fsyncs it. On failure (a full disk, an I/O error) the journal is
  // cut back to its previous length and IoError is returned: the record does not exist.
  core::Status Append(const std::vector<uint8_t>& payload);
  // Empties the journal (after a snapshot took over its records), fsynced.
  core::Status Reset();
  uint64_t size_bytes() const { return size_; }
  const std::string& path() const { return path_; }

 private:
  JournalWriter(std::string path, int fd) : path_(std::move(path)), fd_(fd) {}
  core::Status WriteAt(uint64_t offset, const std::vector<uint8_t>& bytes);
  core::Status CutTo(uint64_t size);
  // Writes the commit block naming `size` bytes and `records` records, fdatasynced.
  core::Status Commit(uint64_t size, uint32_t records);
  core::Status Create();

  std::string path_;
  int fd_ = -1;
  uint64_t size_ = 0;
  uint32_t records_ = 0;
};

}  // namespace fleetmap::aggregator
