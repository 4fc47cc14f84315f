#include "sim/sick/s300_output.h"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>

#include "drivers/sick/scan_conversion.h"

namespace fleetmap::sim::sick {

drivers::sick::S300Telegram S300FromLaserScan(const core::LaserScan& scan, uint32_t scan_number,
                                              size_t beams) {
  drivers::sick::S300Telegram t;
  t.scan_number = scan_number;
  t.telegram_number = static_cast<uint16_t>(scan_number);
  t.beams.resize(beams);
  for (size_t i = 0; i < beams && scan.size() > 0; ++i) {
    const size_t j = beams > 1 ? i * (scan.size() - 1) / (beams - 1) : 0;
    const double cm = scan.IsValidReturn(j) ? std::round(scan.ranges_m[j] * 100.0) : 0.0;
    t.beams[i] = cm > 0x1FFF ? 0 : static_cast<uint16_t>(cm);
  }
  return t;
}

core::Result<size_t> WriteS300Stream(ScanSource& source, int fd, size_t count) {
  size_t written = 0;
  for (; written < count; ++written) {
    std::optional<drivers::sick::ScanTelegram> scan = source.Next();
    if (!scan) break;
    core::Result<core::LaserScan> laser =
        drivers::sick::ToLaserScan(*scan, drivers::sick::ScanConversionOptions(), 0.0);
    if (!laser.ok()) return laser.status();
    const std::vector<uint8_t> bytes =
        drivers::sick::EncodeS300Telegram(S300FromLaserScan(*laser, scan->scan_counter));
    for (size_t at = 0; at < bytes.size();) {
      const ssize_t n = write(fd, bytes.data() + at, bytes.size() - at);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) return core::IoError(std::string("S300 write: ") + std::strerror(errno));
      at += static_cast<size_t>(n);
    }
  }
  return written;
}

}  // namespace fleetmap::sim::sick
