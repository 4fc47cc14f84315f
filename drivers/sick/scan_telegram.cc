#include "drivers/sick/scan_telegram.h"

namespace fleetmap::drivers::sick {

const ScanChannel* ScanTelegram::FindChannel(std::string_view content) const {
  for (const ScanChannel& c : channels16) {
    if (c.content == content) return &c;
  }
  for (const ScanChannel& c : channels8) {
    if (c.content == content) return &c;
  }
  return nullptr;
}

}  // namespace fleetmap::drivers::sick
