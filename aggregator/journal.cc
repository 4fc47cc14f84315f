#include "aggregator/journal.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/byte_io.h"
#include "core/crc32.h"
#include "core/file_io.h"

namespace fleetmap::aggregator {
namespace {

constexpr uint8_t kHeaderMagic[4] = {'F', 'M', 'J', '1'};
constexpr uint8_t kRecordMagic[4] = {'F', 'M', 'J', 'R'};

std::vector<uint8_t> Header() {
  std::vector<uint8_t> out(kHeaderMagic, kHeaderMagic + 4);
  core::ByteWriter(out).U32(kJournalFormatVersion);
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

// Reads the records after the header; stops at the end or at a torn tail.
core::Status ReadRecords(const uint8_t* data, size_t size, JournalContents& c) {
  size_t offset = kJournalHeaderBytes;
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

}  // namespace

core::Result<JournalContents> ReadJournal(const std::string& path, int64_t max_bytes) {
  std::string bytes;
  FLEETMAP_ASSIGN_OR_RETURN(bytes, core::ReadFileBytes(path, max_bytes));
  const auto* data = reinterpret_cast<const uint8_t*>(bytes.data());
  const std::vector<uint8_t> header = Header();
  JournalContents c;
  if (bytes.size() < kJournalHeaderBytes) {
    // Only a journal whose creation was cut short is this short.
    if (std::memcmp(data, header.data(), bytes.size()) != 0)
      return core::DataLoss(path + ": not a fleetmap journal");
    Torn(c, 0, "short file header");
    return c;
  }
  if (std::memcmp(data, header.data(), kJournalHeaderBytes) != 0)
    return core::DataLoss(path + ": not a fleetmap journal (or another format version)");
  c.valid_bytes = kJournalHeaderBytes;
  FLEETMAP_RETURN_IF_ERROR(ReadRecords(data, bytes.size(), c).WithContext(path));
  return c;
}

core::Result<JournalWriter> JournalWriter::Open(const std::string& path, uint64_t valid_bytes) {
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return core::IoError(path + ": cannot open the journal: " + ErrnoText());
  JournalWriter writer(path, fd, 0);
  if (valid_bytes < kJournalHeaderBytes) {
    FLEETMAP_RETURN_IF_ERROR(writer.CutTo(0));
    FLEETMAP_RETURN_IF_ERROR(writer.WriteAt(0, Header()));
    writer.size_ = kJournalHeaderBytes;
  } else {
    FLEETMAP_RETURN_IF_ERROR(writer.CutTo(valid_bytes));
  }
  if (::fsync(fd) != 0) return core::IoError(path + ": fsync failed: " + ErrnoText());
  // Make the file's directory entry durable too (a new journal).
  std::string folder = std::filesystem::path(path).parent_path().string();
  const int dir = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY);
  if (dir >= 0) {
    ::fsync(dir);
    ::close(dir);
  }
  return writer;
}

JournalWriter::JournalWriter(JournalWriter&& o) noexcept
    : path_(std::move(o.path_)), fd_(o.fd_), size_(o.size_) {
  o.fd_ = -1;
}

JournalWriter& JournalWriter::operator=(JournalWriter&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) ::close(fd_);
    path_ = std::move(o.path_), fd_ = o.fd_, size_ = o.size_;
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
  if (!status.ok()) {
    (void)::ftruncate(fd_, static_cast<off_t>(size_));  // best effort: drop the partial record
    return status;
  }
  size_ += record.size();
  return core::OkStatus();
}

core::Status JournalWriter::Reset() {
  FLEETMAP_RETURN_IF_ERROR(CutTo(kJournalHeaderBytes));
  if (::fsync(fd_) != 0) return core::IoError(path_ + ": fsync failed: " + ErrnoText());
  return core::OkStatus();
}

}  // namespace fleetmap::aggregator
