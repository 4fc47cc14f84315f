#include "drivers/sick/cola_frame.h"

#include <algorithm>
#include <cctype>

namespace fleetmap::drivers::sick {

const char* ColaProtocolName(ColaProtocol protocol) {
  return protocol == ColaProtocol::kColaA ? "cola-a" : "cola-b";
}

core::Result<ColaProtocol> ParseColaProtocol(std::string_view text) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (lower == "cola-a" || lower == "a" || lower == "ascii") return ColaProtocol::kColaA;
  if (lower == "cola-b" || lower == "b" || lower == "binary") return ColaProtocol::kColaB;
  return core::InvalidArgument("unknown CoLa protocol '" + lower + "' (cola-a or cola-b)");
}

uint8_t ColaBChecksum(const uint8_t* data, size_t size) {
  uint8_t x = 0;
  for (size_t i = 0; i < size; ++i) x ^= data[i];
  return x;
}

std::string FrameColaA(std::string_view payload) {
  std::string out;
  out.reserve(payload.size() + 2);
  out.push_back(static_cast<char>(kStx));
  out.append(payload);
  out.push_back(static_cast<char>(kEtx));
  return out;
}

std::string FrameColaB(std::string_view payload) {
  std::string out(4, static_cast<char>(kStx));
  const uint32_t n = static_cast<uint32_t>(payload.size());
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>(n >> shift));
  out.append(payload);
  const auto* bytes = reinterpret_cast<const uint8_t*>(payload.data());
  out.push_back(static_cast<char>(ColaBChecksum(bytes, payload.size())));
  return out;
}

std::string FrameTelegram(ColaProtocol protocol, std::string_view payload) {
  return protocol == ColaProtocol::kColaA ? FrameColaA(payload) : FrameColaB(payload);
}

core::Result<ColaCommand> SplitCommand(std::string_view payload) {
  if (payload.size() < 4 || payload[0] != 's' || payload[3] != ' ') {
    return core::InvalidArgument("telegram does not start with a command type like 'sRA '");
  }
  ColaCommand command;
  command.type = payload.substr(0, 3);
  const std::string_view rest = payload.substr(4);
  const size_t space = rest.find(' ');
  command.name = rest.substr(0, space);
  if (space != std::string_view::npos) command.args = rest.substr(space + 1);
  if (command.name.empty()) return core::InvalidArgument("telegram has an empty command name");
  return command;
}

}  // namespace fleetmap::drivers::sick
