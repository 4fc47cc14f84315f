#include "drivers/sick/commands.h"

#include "drivers/sick/cola_field_reader.h"
#include "drivers/sick/cola_field_writer.h"

namespace fleetmap::drivers::sick {

std::string SetAccessModeRequest(ColaProtocol protocol, uint8_t level, uint32_t password_hash) {
  std::string out = "sMN SetAccessMode";
  if (protocol == ColaProtocol::kColaB) {
    out.push_back(' ');
    BinaryFieldWriter w(out);
    w.U8(level);
    w.U32(password_hash);
  } else {
    AsciiFieldWriter w(out);
    w.U8(level);
    w.U32(password_hash);
  }
  return out;
}

std::string SmallReply(ColaProtocol protocol, std::string_view type, std::string_view name,
                       uint8_t value) {
  std::string out(type);
  out.push_back(' ');
  out.append(name);
  if (protocol == ColaProtocol::kColaB) {
    out.push_back(' ');
    out.push_back(static_cast<char>(value));
  } else {
    AsciiFieldWriter(out).U8(value);
  }
  return out;
}

std::string ScanStreamRequest(ColaProtocol protocol, bool start) {
  return SmallReply(protocol, "sEN", "LMDscandata", start ? 1 : 0);
}

std::string ScanPollRequest() { return "sRN LMDscandata"; }
std::string StartMeasurementRequest() { return "sMN LMCstartmeas"; }
std::string StopMeasurementRequest() { return "sMN LMCstopmeas"; }
std::string RunRequest() { return "sMN Run"; }
std::string DeviceStateRequest() { return "sRN SCdevicestate"; }

const char* DeviceStateName(DeviceState state) {
  switch (state) {
    case DeviceState::kBusy:
      return "busy";
    case DeviceState::kReady:
      return "ready";
    case DeviceState::kError:
      return "error";
    case DeviceState::kUnknown:
      break;
  }
  return "unknown";
}

std::string ErrorReply(ColaProtocol protocol, uint8_t code) {
  std::string out = "sFA";
  if (protocol == ColaProtocol::kColaB) {
    out.push_back(' ');
    out.push_back(static_cast<char>(code));
  } else {
    AsciiFieldWriter(out).U8(code);
  }
  return out;
}

namespace {

template <class Reader>
void ReadArguments(Reader& r, ParsedCommand& c) {
  c.value = r.U8();
  if (r.failed()) return;
  c.has_value = true;
  if (c.name == "SetAccessMode" && c.type == "sMN") c.password = r.U32();
}

}  // namespace

core::Result<ParsedCommand> ParseCommand(std::string_view payload, ColaProtocol protocol) {
  ParsedCommand c;
  if (payload.size() >= 4 && payload.substr(0, 4) == "sFA ") {  // sFA has no name, only a code
    c.type = "sFA";
    std::string_view args = payload.substr(4);
    if (protocol == ColaProtocol::kColaB) {
      BinaryFieldReader r(args);
      ReadArguments(r, c);
    } else {
      AsciiFieldReader r(args);
      ReadArguments(r, c);
    }
    return c;
  }
  core::Result<ColaCommand> command = SplitCommand(payload);
  if (!command.ok()) return command.status();
  c.type = std::string(command->type);
  c.name = std::string(command->name);
  if (protocol == ColaProtocol::kColaB) {
    BinaryFieldReader r(command->args);
    ReadArguments(r, c);
  } else {
    AsciiFieldReader r(command->args);
    ReadArguments(r, c);
  }
  return c;
}

}  // namespace fleetmap::drivers::sick
