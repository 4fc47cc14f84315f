// CoLa framing of SICK telegrams over TCP (ports 2111/2112):
//   CoLa-A: STX (0x02) | ASCII payload | ETX (0x03); numbers in hex, fields separated by spaces.
//   CoLa-B: 02 02 02 02 | u32 big-endian payload length | payload | u8 XOR of the payload bytes.
// A payload starts with the command type and name: "sSN LMDscandata ..." (SICK telegram
// listing). Payload bytes are kept in std::string, which holds binary data as well.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/result.h"

namespace fleetmap::drivers::sick {

enum class ColaProtocol { kColaA, kColaB };

const char* ColaProtocolName(ColaProtocol protocol);  // "cola-a", "cola-b"
// Parses "cola-a"/"a"/"ascii" or "cola-b"/"b"/"binary" (case-insensitive).
core::Result<ColaProtocol> ParseColaProtocol(std::string_view text);

constexpr uint8_t kStx = 0x02;
constexpr uint8_t kEtx = 0x03;
constexpr size_t kColaBHeaderBytes = 8;  // four STX and the length

// XOR of every byte: the CoLa-B checksum.
uint8_t ColaBChecksum(const uint8_t* data, size_t size);

std::string FrameColaA(std::string_view payload);
std::string FrameColaB(std::string_view payload);
std::string FrameTelegram(ColaProtocol protocol, std::string_view payload);

// The command type, name and arguments of a payload: "sRA LMDscandata <args>". CoLa-A
// arguments are ASCII tokens, CoLa-B arguments binary; `args` views into the payload.
struct ColaCommand {
  std::string_view type;  // "sRN", "sRA", "sMN", "sAN", "sEN", "sEA", "sSN", "sWN", "sWA", "sFA"
  std::string_view name;  // "LMDscandata", "SetAccessMode", ...
  std::string_view args;  // after the space that ends the name; empty if none
};
// InvalidArgument unless the payload starts with a 3-letter type beginning with 's'.
core::Result<ColaCommand> SplitCommand(std::string_view payload);

}  // namespace fleetmap::drivers::sick
