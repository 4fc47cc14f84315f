#include "aggregator/persistence/journal.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/io/byte_io.h"
#include "core/io/crc32.h"
#include "core/io/file_io.h"

namespace fleetmap::aggregator {
namespace {

constexpr uint8_t kHeaderMagic[4] = {'F', 'M', 'J', '1'};
constexpr uint8_t kRecordMagic[4] = {'F', 'M', 'J', 'R'};

std::vector<uint8_t> Header(uint32_t version) {
  std::vector<uint8_t> out(kHeaderMagic, kHeaderMagic + 4);
  core::ByteWriter(out).U32(version);
  return out;
}

// The commit block: committed bytes, committed records, CRC-32 of those 12 bytes.
std::vector<uint8_t> CommitBlock(uint64_t size, uint32_t records) {
  std::vector<uint8_t> out;
  core::ByteWriter w(out);
  w.U64(size);
  w.U32(records);
  w.U32(core::Crc32(out.data(), out.size()));
  return out;
}

std::string ErrnoText() { return std::strerror(errno); }

bool AllZero(const uint8_t* p, size_t n) {
  return std::all_of(p, p + n, [](uint8_t b) { return b == 0; });
}

void Torn(JournalContents& c, uint64_t offset, const std::string& what) {
  c.torn_tail = true;
  c.torn_detail = what + " at byte " + std::to_string(offset);
}

// Format 1 (no commit block): reads the records after the header; stops at the end or at
// what may be a torn tail.
core::Status ReadRecordsV1(const uint8_t* data, size_t size, JournalContents& c) {
  size_t offset = kJournalV1HeaderBytes;
  while (offset < size) {
    const size_t left = size - offset;
    const uint8_t* p = data + offset;
    if (left < kJournalRecordHeaderBytes) {
      Torn(c, offset, "short record header");
      break;
    }
    if (std::memcmp(p, kRecordMagic, 4) != 0) {
      if (!AllZero(p, left))
        return core::DataLoss("journal corrupt: bad record magic at byte " +
                              std::to_string(offset));
      Torn(c, offset, "zero-filled tail");
      break;
    }
    core::ByteReader r(p + 4, 8);
    const uint32_t length = r.U32(), crc = r.U32();
    if (length > kMaxJournalRecordBytes)
      return core::DataLoss("journal corrupt: record length at byte " + std::to_string(offset));
    if (length > left - kJournalRecordHeaderBytes) {
      Torn(c, offset, "record shorter than its length");
      break;
    }
    const uint8_t* payload = p + kJournalRecordHeaderBytes;
    const size_t end = offset + kJournalRecordHeaderBytes + length;
    if (core::Crc32(payload, length) != crc) {
      if (end != size)
        return core::DataLoss("journal corrupt: record CRC at byte " + std::to_string(offset));
      Torn(c, offset, "last record fails its CRC");
      break;
    }
    c.records.emplace_back(payload, payload + length);
    offset = c.valid_bytes = end;
  }
  return core::OkStatus();
}

// Record `index` (0-based) of the `committed` the header names, at `offset`, is not there
// as committed.
core::Status Damaged(size_t index, uint32_t committed, uint64_t offset, const std::string& what) {
  return core::DataLoss("journal damaged: committed record " + std::to_string(index + 1) + " of " +
                        std::to_string(committed) + " at byte " + std::to_string(offset) + " " +
                        what + "; acknowledged merges are missing (the file is left as it is)");
}

// Format 2: every committed record must be whole; what follows them was never committed.
core::Status ReadRecordsV2(const uint8_t* data, size_t size, JournalContents& c) {
  core::ByteReader block(data + kJournalV1HeaderBytes, 16);
  const uint64_t committed_bytes = block.U64();
  const uint32_t committed = block.U32(), crc = block.U32();
  if (core::Crc32(data + kJournalV1HeaderBytes, 12) != crc || committed_bytes < kJournalHeaderBytes)
    return core::DataLoss("journal damaged: the commit block at byte 8 fails its check");
  uint64_t offset = kJournalHeaderBytes;
  for (size_t i = 0; i < committed; ++i) {
    if (offset + kJournalRecordHeaderBytes > size)
      return Damaged(i, committed, offset,
                     "is cut off (the file ends at byte " + std::to_string(size) + ")");
    const uint8_t* p = data + offset;
    if (std::memcmp(p, kRecordMagic, 4) != 0)
      return Damaged(i, committed, offset,
                     AllZero(p, kJournalRecordHeaderBytes) ? "is zeros" : "has no record magic");
    core::ByteReader r(p + 4, 8);
    const uint32_t length = r.U32(), payload_crc = r.U32();
    const uint64_t end = offset + kJournalRecordHeaderBytes + length;
    if (length > kMaxJournalRecordBytes || end > committed_bytes)
      return Damaged(i, committed, offset, "has a length past the committed end");
    if (end > size)
      return Damaged(i, committed, offset,
                     "is cut off (the file ends at byte " + std::to_string(size) + ")");
    if (core::Crc32(p + kJournalRecordHeaderBytes, length) != payload_crc)
      return Damaged(i, committed, offset, "fails its CRC");
    c.records.emplace_back(p + kJournalRecordHeaderBytes, p + end - offset);
    offset = end;
  }
  if (offset != committed_bytes)
    return core::DataLoss("journal damaged: " + std::to_string(committed) +
                          " committed records end at byte " + std::to_string(offset) +
                          ", the commit block says " + std::to_string(committed_bytes));
  c.valid_bytes = committed_bytes;
  if (size > committed_bytes) Torn(c, committed_bytes, "a record written but never committed");
  return core::OkStatus();
}

}  // namespace

core::Result<JournalContents> ReadJournal(const std::string& path, int64_t max_bytes) {
  std::string bytes;
  FLEETMAP_ASSIGN_OR_RETURN(bytes, core::ReadFileBytes(path, max_bytes));
  const auto* data = reinterpret_cast<const uint8_t*>(bytes.data());
  JournalContents c;
  const std::vector<uint8_t> magic(kHeaderMagic, kHeaderMagic + 4);
  if (bytes.size() < kJournalV1HeaderBytes) {
    // Only a journal whose creation was cut short is this short.
    if (std::memcmp(data, magic.data(), std::min<size_t>(4, bytes.size())) != 0)
      return core::DataLoss(path + ": not a fleetmap journal");
    Torn(c, 0, "short file header");
    return c;
  }
  if (std::memcmp(data, magic.data(), 4) != 0)
    return core::DataLoss(path + ": not a fleetmap journal");
  core::ByteReader version_reader(data + 4, 4);
  c.format_version = version_reader.U32();
  if (c.format_version == 1) {
    c.valid_bytes = kJournalV1HeaderBytes;
    FLEETMAP_RETURN_IF_ERROR(ReadRecordsV1(data, bytes.size(), c).WithContext(path));
    return c;
  }
  if (c.format_version != kJournalFormatVersion)
    return core::DataLoss(path + ": journal format " + std::to_string(c.format_version) +
                          " is not one this version reads");
  if (bytes.size() < kJournalHeaderBytes) {
    // Created, and the crash came before its commit block was written: nothing committed.
    Torn(c, 0, "short file header");
    return c;
  }
  FLEETMAP_RETURN_IF_ERROR(ReadRecordsV2(data, bytes.size(), c).WithContext(path));
  return c;
}

core::Result<JournalSalvage> SalvageJournal(const std::string& path, int64_t max_bytes) {
  std::string bytes;
  FLEETMAP_ASSIGN_OR_RETURN(bytes, core::ReadFileBytes(path, max_bytes));
  const auto* data = reinterpret_cast<const uint8_t*>(bytes.data());
  const size_t size = bytes.size();
  JournalSalvage s;
  if (size < kJournalV1HeaderBytes || std::memcmp(data, kHeaderMagic, 4) != 0) {
    s.damage = "no journal header";
    return s;
  }
  core::ByteReader version_reader(data + 4, 4);
  const uint32_t version = version_reader.U32();
  uint64_t offset = kJournalV1HeaderBytes;
  if (version == kJournalFormatVersion) {
    offset = kJournalHeaderBytes;
    if (size >= kJournalHeaderBytes) {
      core::ByteReader block(data + kJournalV1HeaderBytes, 16);
      block.U64();
      const uint32_t committed = block.U32(), crc = block.U32();
      if (core::Crc32(data + kJournalV1HeaderBytes, 12) == crc) s.committed_records = committed;
    }
  } else if (version != 1) {
    s.damage = "journal format " + std::to_string(version) + " is not one this version reads";
    return s;
  }
  while (offset < size && (s.committed_records < 0 ||
                           static_cast<int64_t>(s.records.size()) < s.committed_records)) {
    const std::string where =
        "record " + std::to_string(s.records.size() + 1) + " at byte " + std::to_string(offset);
    if (offset + kJournalRecordHeaderBytes > size) {
      s.damage = where + " is cut off";
      break;
    }
    const uint8_t* p = data + offset;
    core::ByteReader r(p + 4, 8);
    const uint32_t length = r.U32(), payload_crc = r.U32();
    const uint64_t end = offset + kJournalRecordHeaderBytes + length;
    if (std::memcmp(p, kRecordMagic, 4) != 0 || length > kMaxJournalRecordBytes || end > size) {
      s.damage =
          where + (std::memcmp(p, kRecordMagic, 4) != 0 ? " has no record magic" : " is cut off");
      break;
    }
    if (core::Crc32(p + kJournalRecordHeaderBytes, length) != payload_crc) {
      s.damage = where + " fails its CRC";
      break;
    }
    s.records.emplace_back(p + kJournalRecordHeaderBytes, p + end - offset);
    offset = end;
  }
  if (s.damage.empty() && s.committed_records > static_cast<int64_t>(s.records.size()))
    s.damage = "the file ends after " + std::to_string(s.records.size()) + " records";
  if (s.damage.empty() && s.committed_records < 0 && version == kJournalFormatVersion)
    s.damage = "the commit block at byte 8 fails its check";
  return s;
}

namespace {

// Makes the file's directory entry durable (a new or renamed journal).
void SyncFolder(const std::string& path) {
  const std::string folder = std::filesystem::path(path).parent_path().string();
  const int dir = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY);
  if (dir >= 0) {
    ::fsync(dir);
    ::close(dir);
  }
}

// A format 1 journal's records, written as a format 2 journal renamed over it; its length.
core::Result<uint64_t> Upgrade(const std::string& path, const JournalContents& found) {
  const std::string tmp = path + ".upgrade";
  uint64_t size = 0;
  {
    auto writer = JournalWriter::Open(tmp, JournalContents{});
    if (!writer.ok()) return writer.status();
    for (const auto& record : found.records) FLEETMAP_RETURN_IF_ERROR(writer->Append(record));
    size = writer->size_bytes();
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0)
    return core::IoError(path + ": cannot replace the format 1 journal: " + ErrnoText());
  SyncFolder(path);
  return size;
}

}  // namespace

core::Result<JournalWriter> JournalWriter::Open(const std::string& path,
                                                const JournalContents& found) {
  // ReadJournal found good records (or at least a header) exactly when valid_bytes > 0.
  uint64_t size = found.valid_bytes;
  if (size > 0 && found.format_version == 1) FLEETMAP_ASSIGN_OR_RETURN(size, Upgrade(path, found));
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return core::IoError(path + ": cannot open the journal: " + ErrnoText());
  JournalWriter writer(path, fd);
  if (size == 0) {
    FLEETMAP_RETURN_IF_ERROR(writer.Create());
  } else {
    writer.records_ = static_cast<uint32_t>(found.records.size());
    FLEETMAP_RETURN_IF_ERROR(writer.CutTo(size));  // drops what was never committed
    if (::fsync(fd) != 0) return core::IoError(path + ": fsync failed: " + ErrnoText());
  }
  SyncFolder(path);
  return writer;
}

core::Status JournalWriter::Create() {
  FLEETMAP_RETURN_IF_ERROR(CutTo(0));
  std::vector<uint8_t> header = Header(kJournalFormatVersion);
  const std::vector<uint8_t> block = CommitBlock(kJournalHeaderBytes, 0);
  header.insert(header.end(), block.begin(), block.end());
  FLEETMAP_RETURN_IF_ERROR(WriteAt(0, header));
  size_ = kJournalHeaderBytes;
  records_ = 0;
  if (::fsync(fd_) != 0) return core::IoError(path_ + ": fsync failed: " + ErrnoText());
  return core::OkStatus();
}

core::Status JournalWriter::Commit(uint64_t size, uint32_t records) {
  FLEETMAP_RETURN_IF_ERROR(WriteAt(kJournalV1HeaderBytes, CommitBlock(size, records)));
  if (::fdatasync(fd_) != 0) return core::IoError(path_ + ": journal fsync failed: " + ErrnoText());
  return core::OkStatus();
}

JournalWriter::JournalWriter(JournalWriter&& o) noexcept
    : path_(std::move(o.path_)), fd_(o.fd_), size_(o.size_), records_(o.records_) {
  o.fd_ = -1;
}

JournalWriter& JournalWriter::operator=(JournalWriter&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) ::close(fd_);
    path_ = std::move(o.path_), fd_ = o.fd_, size_ = o.size_, records_ = o.records_;
    o.fd_ = -1;
  }
  return *this;
}

JournalWriter::~JournalWriter() {
  if (fd_ >= 0) ::close(fd_);
}

core::Status JournalWriter::WriteAt(uint64_t offset, const std::vector<uint8_t>& bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n =
        ::pwrite(fd_, bytes.data() + done, bytes.size() - done, static_cast<off_t>(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return core::IoError(path_ + ": journal write failed: " + ErrnoText());
    done += static_cast<size_t>(n);
  }
  return core::OkStatus();
}

core::Status JournalWriter::CutTo(uint64_t size) {
  if (::ftruncate(fd_, static_cast<off_t>(size)) != 0)
    return core::IoError(path_ + ": cannot truncate the journal: " + ErrnoText());
  size_ = size;
  return core::OkStatus();
}

core::Status JournalWriter::Append(const std::vector<uint8_t>& payload) {
  if (payload.size() > kMaxJournalRecordBytes)
    return core::OutOfRange(path_ + ": journal record too large");
  std::vector<uint8_t> record(kRecordMagic, kRecordMagic + 4);
  record.reserve(kJournalRecordHeaderBytes + payload.size());
  core::ByteWriter w(record);
  w.U32(static_cast<uint32_t>(payload.size()));
  w.U32(core::Crc32(payload.data(), payload.size()));
  w.Bytes(payload.data(), payload.size());
  core::Status status = WriteAt(size_, record);
  if (status.ok() && ::fdatasync(fd_) != 0)
    status = core::IoError(path_ + ": journal fsync failed: " + ErrnoText());
  // Written: now committed. Until the commit block names it, a crash drops the record.
  if (status.ok()) status = Commit(size_ + record.size(), records_ + 1);
  if (!status.ok()) {
    (void)::ftruncate(fd_, static_cast<off_t>(size_));  // best effort: drop the partial record
    return status;
  }
  size_ += record.size();
  ++records_;
  return core::OkStatus();
}

core::Status JournalWriter::Reset() {
  // Uncommit first: a crash before the cut leaves records nothing names (dropped as a tail).
  FLEETMAP_RETURN_IF_ERROR(Commit(kJournalHeaderBytes, 0));
  records_ = 0;
  FLEETMAP_RETURN_IF_ERROR(CutTo(kJournalHeaderBytes));
  if (::fsync(fd_) != 0) return core::IoError(path_ + ": fsync failed: " + ErrnoText());
  return core::OkStatus();
}

}  // namespace fleetmap::aggregator
