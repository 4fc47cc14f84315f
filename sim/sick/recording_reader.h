// Reads recorded SICK telegrams from the files real scanners were captured in (the fixtures in
// $FLEETMAP_DATA_DIR/sick, SOURCES.md there; FLEETMAP_DATA_DIR is the folder of real
// recordings, tests/support/data_dir.h):
//   *.pcapng       pcapng capture (Ethernet, IPv4, TCP): segments are ordered by sequence
//                  number per direction, the streams reassembled and cut into telegrams.
//   *.pcapng.json  sick_scan_xd's pcap_json_converter output: one framed telegram per entry.
//   *.dat          pysicktim's dump of CoLa-A "sRA LMDscandata" replies.
// The protocol of each stream is detected from its first bytes.
#pragma once

#include <string>
#include <vector>

#include "core/result.h"
#include "drivers/sick/cola_frame.h"
#include "drivers/sick/telegram_splitter.h"

namespace fleetmap::sim::sick {

struct RecordedTelegram {
  double time_s = 0.0;       // capture time (relative or epoch, as the file has it)
  bool from_scanner = true;  // false: sent by the host (requests)
  drivers::sick::ColaProtocol protocol = drivers::sick::ColaProtocol::kColaB;
  std::string payload;  // without framing
};

struct Recording {
  std::vector<RecordedTelegram> telegrams;
  drivers::sick::TelegramSplitterStats framing;  // summed over every stream of the file
};

// Dispatches on the file name's ending.
core::Result<Recording> ReadRecording(const std::string& path);
core::Result<Recording> ReadPcapng(const std::string& path);
core::Result<Recording> ReadPcapJson(const std::string& path);
core::Result<Recording> ReadPysicktimDump(const std::string& path);

// Only the LMDscandata scans sent by the scanner.
std::vector<RecordedTelegram> ScanTelegrams(const Recording& recording);

}  // namespace fleetmap::sim::sick
