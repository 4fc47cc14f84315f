#include "drivers/sick/scan_telegram_codec.h"

#include "drivers/sick/cola_field_reader.h"
#include "drivers/sick/cola_field_writer.h"

namespace fleetmap::drivers::sick {
namespace {

core::Status Truncated(const char* field) {
  return core::DataLoss(std::string("LMDscandata: truncated or malformed at ") + field);
}

template <class Reader>
core::Status ParseHeader(Reader& r, ScanTelegram& t) {
  t.version = r.U16();
  t.device_number = r.U16();
  t.serial_number = r.U32();
  t.device_status[0] = r.U8();
  t.device_status[1] = r.U8();
  t.telegram_counter = r.U16();
  t.scan_counter = r.U16();
  t.time_since_startup_us = r.U32();
  t.time_of_transmission_us = r.U32();
  t.input_status[0] = r.U8();
  t.input_status[1] = r.U8();
  t.output_status[0] = r.U8();
  t.output_status[1] = r.U8();
  t.reserved = r.U16();
  t.scan_frequency_centihz = r.U32();
  t.measurement_frequency_100hz = r.U32();
  return r.failed() ? Truncated("header") : core::OkStatus();
}

template <class Reader>
core::Status ParseEncoders(Reader& r, ScanTelegram& t) {
  const uint16_t n = r.U16();
  if (r.failed()) return Truncated("number of encoders");
  if (n > kMaxScanEncoders) {
    return core::InvalidArgument("LMDscandata: " + std::to_string(n) + " encoders (at most " +
                                 std::to_string(kMaxScanEncoders) + ")");
  }
  t.encoders.resize(n);
  for (ScanEncoder& e : t.encoders) {
    e.position_ticks = r.U32();
    e.speed_ticks_per_mm = r.U16();
  }
  return r.failed() ? Truncated("encoders") : core::OkStatus();
}

template <class Reader>
core::Status ParseChannels(Reader& r, bool sixteen_bit, std::vector<ScanChannel>& channels) {
  const char* what = sixteen_bit ? "16-bit channels" : "8-bit channels";
  const uint16_t n = r.U16();
  if (r.failed()) return Truncated(what);
  if (n > kMaxScanChannels) {
    return core::InvalidArgument("LMDscandata: " + std::to_string(n) + " " + what);
  }
  channels.resize(n);
  for (ScanChannel& c : channels) {
    c.content = r.Fixed(5);
    c.scale_factor = r.F32();
    c.scale_offset = r.F32();
    c.start_angle_1e4deg = r.I32();
    c.angular_step_1e4deg = r.U16();
    const uint16_t count = r.U16();
    if (r.failed()) return Truncated(what);
    if (count > r.MaxValuesLeft()) {
      return core::DataLoss("LMDscandata: channel " + c.content + " claims " +
                            std::to_string(count) + " values, more than the telegram holds");
    }
    c.values.resize(count);
    const bool ok =
        sixteen_bit ? r.Values16(c.values.data(), count) : r.Values8(c.values.data(), count);
    if (!ok) return Truncated(c.content.c_str());
  }
  return core::OkStatus();
}

// A 0/1 flag that announces an optional block.
template <class Reader>
core::Result<bool> Flag(Reader& r, const char* block) {
  const uint16_t v = r.U16();
  if (r.failed()) return Truncated(block);
  if (v > 1) {
    return core::InvalidArgument(std::string("LMDscandata: ") + block + " flag is " +
                                 std::to_string(v));
  }
  return v == 1;
}

template <class Reader>
core::Status ParseOptionalBlocks(Reader& r, ScanTelegram& t) {
  bool present = false;
  FLEETMAP_ASSIGN_OR_RETURN(present, Flag(r, "position"));
  t.position.reset();
  if (present) {
    ScanPosition p;
    p.x = r.F32(), p.y = r.F32(), p.z = r.F32();
    p.x_rot = r.F32(), p.y_rot = r.F32(), p.z_rot = r.F32();
    p.rotation_type = r.U8();
    t.position = p;
  }
  FLEETMAP_ASSIGN_OR_RETURN(present, Flag(r, "name"));
  t.name.reset();
  if (present) t.name = r.String8();
  FLEETMAP_ASSIGN_OR_RETURN(present, Flag(r, "comment"));
  t.comment.reset();
  if (present) t.comment = r.String8();
  if (r.failed()) return Truncated("position, name or comment");
  FLEETMAP_ASSIGN_OR_RETURN(present, Flag(r, "time"));
  t.clock.reset();
  if (present) {
    ScanClock c;
    c.year = r.U16();
    c.month = r.U8(), c.day = r.U8(), c.hour = r.U8(), c.minute = r.U8(), c.second = r.U8();
    c.microsecond = r.U32();
    t.clock = c;
  }
  FLEETMAP_ASSIGN_OR_RETURN(present, Flag(r, "event"));
  t.event.reset();
  if (present) {
    ScanEventInfo e;
    e.type = r.Fixed(4);
    e.encoder_position = r.U32();
    e.time_us = r.U32();
    e.angular_position_1e4deg = r.I32();
    t.event = e;
  }
  return r.failed() ? Truncated("time or event") : core::OkStatus();
}

template <class Reader>
core::Status ParseBody(Reader& r, ScanTelegram& t) {
  FLEETMAP_RETURN_IF_ERROR(ParseHeader(r, t));
  FLEETMAP_RETURN_IF_ERROR(ParseEncoders(r, t));
  FLEETMAP_RETURN_IF_ERROR(ParseChannels(r, /*sixteen_bit=*/true, t.channels16));
  FLEETMAP_RETURN_IF_ERROR(ParseChannels(r, /*sixteen_bit=*/false, t.channels8));
  return ParseOptionalBlocks(r, t);
}

template <class Writer>
void WriteChannels(Writer& w, bool sixteen_bit, const std::vector<ScanChannel>& channels) {
  w.U16(static_cast<uint16_t>(channels.size()));
  for (const ScanChannel& c : channels) {
    w.Fixed(c.content);
    w.F32(c.scale_factor);
    w.F32(c.scale_offset);
    w.I32(c.start_angle_1e4deg);
    w.U16(c.angular_step_1e4deg);
    w.U16(static_cast<uint16_t>(c.values.size()));
    for (const uint16_t v : c.values) sixteen_bit ? w.Value16(v) : w.Value8(v);
  }
}

template <class Writer>
void WriteOptionalBlocks(Writer& w, const ScanTelegram& t) {
  w.U16(t.position.has_value());
  if (const auto& p = t.position) {
    for (const float f : {p->x, p->y, p->z, p->x_rot, p->y_rot, p->z_rot}) w.F32(f);
    w.U8(p->rotation_type);
  }
  w.U16(t.name.has_value());
  if (t.name) w.String8(*t.name);
  w.U16(t.comment.has_value());
  if (t.comment) w.String8(*t.comment);
  w.U16(t.clock.has_value());
  if (const auto& c = t.clock) {
    w.U16(c->year);
    for (const uint8_t b : {c->month, c->day, c->hour, c->minute, c->second}) w.U8(b);
    w.U32(c->microsecond);
  }
  w.U16(t.event.has_value());
  if (const auto& e = t.event) {
    w.Fixed(e->type);
    w.U32(e->encoder_position);
    w.U32(e->time_us);
    w.I32(e->angular_position_1e4deg);
  }
}

template <class Writer>
void WriteBody(Writer& w, const ScanTelegram& t) {
  w.U16(t.version);
  w.U16(t.device_number);
  w.U32(t.serial_number);
  w.U8(t.device_status[0]), w.U8(t.device_status[1]);
  w.U16(t.telegram_counter);
  w.U16(t.scan_counter);
  w.U32(t.time_since_startup_us);
  w.U32(t.time_of_transmission_us);
  w.U8(t.input_status[0]), w.U8(t.input_status[1]);
  w.U8(t.output_status[0]), w.U8(t.output_status[1]);
  w.U16(t.reserved);
  w.U32(t.scan_frequency_centihz);
  w.U32(t.measurement_frequency_100hz);
  w.U16(static_cast<uint16_t>(t.encoders.size()));
  for (const ScanEncoder& e : t.encoders) {
    w.U32(e.position_ticks);
    w.U16(e.speed_ticks_per_mm);
  }
  WriteChannels(w, true, t.channels16);
  WriteChannels(w, false, t.channels8);
  WriteOptionalBlocks(w, t);
}

}  // namespace

bool IsScanTelegram(std::string_view payload) {
  const auto command = SplitCommand(payload);
  return command.ok() && command->name == "LMDscandata" &&
         (command->type == "sRA" || command->type == "sSN");
}

core::Status ParseScanTelegramInto(std::string_view payload, ColaProtocol protocol,
                                   ScanTelegram& out) {
  core::Result<ColaCommand> command = SplitCommand(payload);
  if (!command.ok()) return command.status();
  if (command->name != "LMDscandata" || (command->type != "sRA" && command->type != "sSN")) {
    return core::InvalidArgument("not an LMDscandata scan: " + std::string(command->type) + " " +
                                 std::string(command->name));
  }
  if (protocol == ColaProtocol::kColaB) {
    BinaryFieldReader reader(command->args);
    return ParseBody(reader, out);
  }
  AsciiFieldReader reader(command->args);
  return ParseBody(reader, out);
}

core::Result<ScanTelegram> ParseScanTelegram(std::string_view payload, ColaProtocol protocol) {
  ScanTelegram telegram;
  FLEETMAP_RETURN_IF_ERROR(ParseScanTelegramInto(payload, protocol, telegram));
  return telegram;
}

std::string EncodeScanTelegram(const ScanTelegram& telegram, ColaProtocol protocol,
                               std::string_view command_type) {
  std::string out(command_type);
  out += " LMDscandata";
  if (protocol == ColaProtocol::kColaB) {
    out.push_back(' ');
    BinaryFieldWriter writer(out);
    WriteBody(writer, telegram);
  } else {
    AsciiFieldWriter writer(out);
    WriteBody(writer, telegram);
  }
  return out;
}

}  // namespace fleetmap::drivers::sick
