// The request telegrams the driver sends and the replies it understands (SICK telegram
// listing): login with SetAccessMode, start of the measurement, return to run mode, start and
// stop of streaming, single poll, device state.
//   sMN SetAccessMode <level> <password hash>   ->  sAN SetAccessMode <1 ok | 0 refused>
//   sMN LMCstartmeas / LMCstopmeas             ->  sAN LMCstartmeas <0 ok | error code>
//   sMN Run                                    ->  sAN Run <1 ok | 0 refused>
//   sEN LMDscandata 1 / 0                      ->  sEA LMDscandata 1 / 0, then sSN scans
//   sRN LMDscandata                            ->  sRA LMDscandata <scan>
//   sRN SCdevicestate                          ->  sRA SCdevicestate <0 busy | 1 ready | 2 error>
//   any refused request                        ->  sFA <error code>
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "core/result.h"
#include "drivers/sick/cola_frame.h"

namespace fleetmap::drivers::sick {

// User level 3 ("authorized client") and its documented default password hash.
constexpr uint8_t kAuthorizedClientLevel = 3;
constexpr uint32_t kAuthorizedClientPasswordHash = 0xF4724744;

// Payloads (without framing).
std::string SetAccessModeRequest(ColaProtocol protocol, uint8_t level = kAuthorizedClientLevel,
                                 uint32_t password_hash = kAuthorizedClientPasswordHash);
std::string ScanStreamRequest(ColaProtocol protocol, bool start);  // sEN LMDscandata 1/0
std::string ScanPollRequest();                                     // sRN LMDscandata
std::string StartMeasurementRequest();                             // sMN LMCstartmeas
std::string StopMeasurementRequest();                              // sMN LMCstopmeas
std::string RunRequest();                                          // sMN Run
std::string DeviceStateRequest();                                  // sRN SCdevicestate

// SCdevicestate values.
enum class DeviceState : int { kUnknown = -1, kBusy = 0, kReady = 1, kError = 2 };
const char* DeviceStateName(DeviceState state);

// Replies with one small numeric argument ("sAN SetAccessMode 1", "sEA LMDscandata 0").
std::string SmallReply(ColaProtocol protocol, std::string_view type, std::string_view name,
                       uint8_t value);
// "sFA <code>": the device refused a request.
std::string ErrorReply(ColaProtocol protocol, uint8_t code);

// A parsed request or short reply: the command and its first numeric argument if any.
struct ParsedCommand {
  std::string type;
  std::string name;
  bool has_value = false;
  uint32_t value = 0;     // first argument (level, start/stop, success)
  uint32_t password = 0;  // SetAccessMode only
};
core::Result<ParsedCommand> ParseCommand(std::string_view payload, ColaProtocol protocol);

}  // namespace fleetmap::drivers::sick
