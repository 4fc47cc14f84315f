#include "core/io/file_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace fleetmap::core {
namespace {

std::string ErrnoText() { return std::strerror(errno); }

Status WriteAll(int fd, std::string_view bytes, bool sync) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return IoError("write failed: " + ErrnoText());
    done += static_cast<size_t>(n);
  }
  if (sync && ::fsync(fd) != 0) return IoError("fsync failed: " + ErrnoText());
  return OkStatus();
}

void SyncFolderOf(const std::string& path) {
  std::string folder = std::filesystem::path(path).parent_path().string();
  if (folder.empty()) folder = ".";
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;  // best effort: the rename itself has succeeded
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

Result<std::string> ReadFileBytes(const std::string& path, int64_t max_bytes) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) return NotFound(path + ": file does not exist");
  if (!std::filesystem::is_regular_file(status)) return IoError(path + ": not a regular file");
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return IoError(path + ": cannot read the size: " + ec.message());
  if (size > static_cast<uintmax_t>(max_bytes)) {
    return OutOfRange(path + ": file of " + std::to_string(size) + " bytes exceeds the limit of " +
                      std::to_string(max_bytes) + " bytes");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return IoError(path + ": cannot open: " + ErrnoText());
  std::string bytes(static_cast<size_t>(size), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  if (static_cast<uintmax_t>(in.gcount()) != size) return IoError(path + ": read failed");
  return bytes;
}

Status WriteFileAtomically(const std::string& path, std::string_view bytes, Durability durability) {
  const bool sync = durability == Durability::kPowerLoss;
  std::string temp_path = path + ".tmp.XXXXXX";
  const int fd = ::mkstemp(temp_path.data());
  if (fd < 0) return IoError(path + ": cannot create a temporary file: " + ErrnoText());
  Status status = ::fchmod(fd, 0644) == 0 ? OkStatus() : IoError("chmod failed: " + ErrnoText());
  if (status.ok()) status = WriteAll(fd, bytes, sync);
  if (::close(fd) != 0 && status.ok()) status = IoError("close failed: " + ErrnoText());
  if (status.ok() && ::rename(temp_path.c_str(), path.c_str()) != 0) {
    status = IoError("cannot rename the temporary file into place: " + ErrnoText());
  }
  if (!status.ok()) {
    ::unlink(temp_path.c_str());
    return status.WithContext(path);
  }
  if (sync) SyncFolderOf(path);
  return OkStatus();
}

}  // namespace fleetmap::core
