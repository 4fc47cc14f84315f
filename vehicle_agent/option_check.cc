#include "vehicle_agent/option_check.h"

#include <sstream>

namespace fleetmap::vehicle_agent {

core::Status CheckOption(bool ok, const std::string& field, double value,
                         const std::string& requirement) {
  if (ok) return core::OkStatus();
  std::ostringstream message;
  message << field << " = " << value << ": must be " << requirement;
  return core::InvalidArgument(message.str());
}

}  // namespace fleetmap::vehicle_agent
