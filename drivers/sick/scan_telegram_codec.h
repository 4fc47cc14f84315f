// Parsing and writing of LMDscandata payloads in CoLa-A and CoLa-B. One template walks the
// fields for both protocols, so the two cannot disagree. Parsing checks every count against
// the bytes that remain before it allocates, and every error names the field where the
// telegram went wrong.
#pragma once

#include <string>
#include <string_view>

#include "core/result.h"
#include "drivers/sick/cola_frame.h"
#include "drivers/sick/scan_telegram.h"

namespace fleetmap::drivers::sick {

// Limits on counts a real scanner never exceeds; larger counts are corrupt telegrams.
constexpr uint16_t kMaxScanEncoders = 8;
constexpr uint16_t kMaxScanChannels = 16;

// Parses a payload "sRA LMDscandata ..." or "sSN LMDscandata ..." (without framing).
core::Result<ScanTelegram> ParseScanTelegram(std::string_view payload, ColaProtocol protocol);
// The same into `out`, reusing its vectors: no allocation once they have grown.
core::Status ParseScanTelegramInto(std::string_view payload, ColaProtocol protocol,
                                   ScanTelegram& out);

// True if the payload is an LMDscandata scan ("sRA"/"sSN" and the name).
bool IsScanTelegram(std::string_view payload);

// Writes the payload of `telegram` with the command type "sSN" (event) or "sRA" (poll reply).
std::string EncodeScanTelegram(const ScanTelegram& telegram, ColaProtocol protocol,
                               std::string_view command_type = "sSN");

}  // namespace fleetmap::drivers::sick
