// The append-only journal of accepted merges. Every record is written and fsynced before the
// merge is acknowledged; on start the journal is read back and replayed after the snapshot.
// File layout (little-endian):
//
//   header  "FMJ1" then u32 format version (kJournalFormatVersion)
//   record  u32 magic "FMJR", u32 payload length, u32 CRC-32 of the payload, the payload
//
// A crash can leave the last record half written (a torn tail): a short header, a payload
// shorter than its length, a last record whose CRC fails, or zeros where the record should
// be. Such a tail was never acknowledged; it is dropped and cut off before the next append.
// A bad record followed by good data is corruption: reading fails with DataLoss.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"

namespace fleetmap::aggregator {

constexpr uint32_t kJournalFormatVersion = 1;
constexpr size_t kJournalHeaderBytes = 8;
constexpr size_t kJournalRecordHeaderBytes = 12;
constexpr uint32_t kMaxJournalRecordBytes = 64u << 20;

struct JournalContents {
  std::vector<std::vector<uint8_t>> records;  // payloads, in order
  uint64_t valid_bytes = 0;  // the file length up to the end of the last good record
  bool torn_tail = false;    // a half-written last record was found and dropped
  std::string torn_detail;   // what the tail looked like, for the log
};

// NotFound when the file does not exist; DataLoss for corruption; OutOfRange over max_bytes.
core::Result<JournalContents> ReadJournal(const std::string& path, int64_t max_bytes);

class JournalWriter {
 public:
  // Opens (or creates) the journal for appending and cuts it to `valid_bytes` (what
  // ReadJournal found good; 0 for a new journal), so a torn tail is gone before the next
  // record. IoError naming the path on failure.
  static core::Result<JournalWriter> Open(const std::string& path, uint64_t valid_bytes);

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
  JournalWriter(std::string path, int fd, uint64_t size)
      : path_(std::move(path)), fd_(fd), size_(size) {}
  core::Status WriteAt(uint64_t offset, const std::vector<uint8_t>& bytes);
  core::Status CutTo(uint64_t size);

  std::string path_;
  int fd_ = -1;
  uint64_t size_ = 0;
};

}  // namespace fleetmap::aggregator
