// Seeds of the sensor and log targets, extracted from the real recordings in the data folder
// (SOURCES.md there says where each file comes from) and completed with our own encoders'
// telegrams, so that every field the parsers know occurs in some seed.
#include <zlib.h>

#include "core/io/file_io.h"
#include "drivers/can/candump_log.h"
#include "drivers/sick/commands.h"
#include "drivers/sick/scan_conversion.h"
#include "drivers/sick/scan_telegram_codec.h"
#include "eval/carmen/carmen_log.h"
#include "fuzz/seed_sources.h"
#include "sim/sick/recording_reader.h"
#include "sim/sick/s300_output.h"
#include "sim/sick/tcp_reassembly.h"

namespace fleetmap::fuzz {
namespace {

namespace fs = std::filesystem;
namespace sick = drivers::sick;

// Stream targets take the piece size as their first byte: 255 whole, 38 about one TCP
// segment (1445 bytes), 0 byte by byte.
std::string Stream(uint8_t piece, const std::string& bytes) { return char(piece) + bytes; }

// The first `n` lines of a text file that are not comments, gzip-compressed or not.
std::vector<std::string> FirstLines(const fs::path& path, size_t n) {
  std::vector<std::string> lines;
  gzFile file = gzopen(path.c_str(), "rb");  // reads plain files as they are
  if (file == nullptr) return lines;
  std::string line;
  char buffer[4096];
  while (lines.size() < n && gzgets(file, buffer, sizeof(buffer)) != nullptr) {
    line += buffer;
    if (line.back() != '\n') continue;  // a line longer than the buffer
    if (line[0] != '#') lines.push_back(line);
    line.clear();
  }
  gzclose(file);
  return lines;
}

std::vector<sim::sick::RecordedTelegram> Recording(const fs::path& path) {
  auto recording = sim::sick::ReadRecording(path.string());
  return recording.ok() ? recording->telegrams : std::vector<sim::sick::RecordedTelegram>{};
}

void AddRecordedStreams(SeedCorpus& corpus, const fs::path& sick_dir) {
  for (const char* file :
       {"sick_scan_xd/20210302_lms111.pcapng.json", "sick_scan_xd/20210302_lms511.pcapng.json",
        "sick_scan_xd/20210125-tim781s-scandata.pcapng.json",
        "sick_scan_xd/20221018_rms_1xxx_ascii_rms2_objects.pcapng.json", "pysicktim/sim.dat"}) {
    const std::vector<sim::sick::RecordedTelegram> telegrams = Recording(sick_dir / file);
    if (telegrams.empty()) continue;
    const std::string name = fs::path(file).stem().stem().string();
    // The startup dialogue and the first scan, framed as on the wire.
    std::string startup;
    bool scan_added = false;
    for (size_t i = 0; i < telegrams.size(); ++i) {
      const sim::sick::RecordedTelegram& t = telegrams[i];
      const bool scan = sick::IsScanTelegram(t.payload);
      if (i < 12 && !scan) startup += sick::FrameTelegram(t.protocol, t.payload);
      if (!scan || scan_added) continue;
      scan_added = true;
      const bool b = t.protocol == sick::ColaProtocol::kColaB;
      corpus.Add("lmd_scandata", name, char(b ? 1 : 0) + t.payload);
      startup += sick::FrameTelegram(t.protocol, t.payload);
    }
    corpus.Add(telegrams[0].protocol == sick::ColaProtocol::kColaB ? "cola_b" : "cola_a", name,
               Stream(255, startup));
  }
}

// Raw TCP segments of a capture: one telegram arrives split in two segments.
void AddCapturedSegments(SeedCorpus& corpus, const fs::path& sick_dir) {
  auto bytes = core::ReadFileBytes((sick_dir / "sick_scan_xd/test.pcapng").string(), 16 << 20);
  if (!bytes.ok()) return;
  auto streams = sim::sick::ReassemblePcapng(*bytes);
  if (!streams.ok()) return;
  for (const sim::sick::TcpStream& s : *streams) {
    if (s.src_port != 2112 || s.segments.size() < 3) continue;
    std::string three;
    for (size_t i = 0; i < 3; ++i) three += s.segments[i].bytes;
    corpus.Add("cola_b", "tim781s_tcp_segments", Stream(38, three));
  }
}

// Our own telegrams: every optional LMDscandata block, commands, replies, both protocols.
void AddEncodedTelegrams(SeedCorpus& corpus, const std::vector<core::LaserScan>& scans) {
  sick::ScanTelegram t = sick::FromLaserScan(scans.empty() ? core::LaserScan() : scans[0]);
  t.encoders.push_back({123456, 7});
  t.channels8.push_back(t.channels16.front());
  t.channels8.back().content = "RSSI1";
  t.channels8.back().values.resize(t.channels16.front().values.size(), 200);
  t.position = sick::ScanPosition{1, 2, 3, 0.1f, 0.2f, 0.3f, 1};
  t.name = "fleet scanner";
  t.comment = "seed";
  t.clock = sick::ScanClock{2024, 5, 6, 7, 8, 9, 123456};
  t.event = sick::ScanEventInfo{"FDIN", 1, 2, -3};
  for (const auto protocol : {sick::ColaProtocol::kColaA, sick::ColaProtocol::kColaB}) {
    const bool b = protocol == sick::ColaProtocol::kColaB;
    const std::string target = b ? "cola_b" : "cola_a";
    const std::string scan = sick::EncodeScanTelegram(t, protocol, "sRA");
    corpus.Add("lmd_scandata", b ? "all_blocks_b" : "all_blocks_a", char(b ? 1 : 0) + scan);
    std::string dialogue =
        sick::FrameTelegram(protocol, sick::SetAccessModeRequest(protocol)) +
        sick::FrameTelegram(protocol, sick::SmallReply(protocol, "sAN", "SetAccessMode", 1)) +
        sick::FrameTelegram(protocol, sick::ScanStreamRequest(protocol, true)) +
        sick::FrameTelegram(protocol, sick::ErrorReply(protocol, 4)) + "garbage" +
        sick::FrameTelegram(protocol, scan);
    corpus.Add(target, "dialogue_whole", Stream(255, dialogue));
    corpus.Add(target, "dialogue_bytewise", Stream(0, dialogue));
  }
}

void AddS300(SeedCorpus& corpus, const std::vector<core::LaserScan>& scans) {
  if (scans.empty()) return;
  const auto s300 = sick::EncodeS300Telegram(sim::sick::S300FromLaserScan(scans[0], 17));
  const auto s3000 = sick::EncodeS300Telegram(sim::sick::S300FromLaserScan(scans.back(), 18, 381));
  const std::string a(s300.begin(), s300.end()), b(s3000.begin(), s3000.end());
  corpus.Add("s300", "s300_541_beams", Stream(255, a));
  corpus.Add("s300", "s3000_381_beams", Stream(255, b));
  corpus.Add("s300", "stream_with_garbage", Stream(11, "\xFF\x00\x00" + a.substr(100) + a + b));
}

}  // namespace

std::vector<core::LaserScan> RealScans(const SeedInputs& in) {
  std::vector<core::LaserScan> scans;
  for (const char* file :
       {"sick/sick_scan_xd/20210302_lms511.pcapng.json", "sick/pysicktim/sim.dat"}) {
    for (const sim::sick::RecordedTelegram& t : Recording(in.data_dir / file)) {
      auto telegram = sick::ParseScanTelegram(t.payload, t.protocol);
      auto scan =
          telegram.ok() ? sick::ToLaserScan(*telegram, {}, 1700000000.0) : telegram.status();
      if (!scan.ok()) continue;
      scans.push_back(std::move(scan).value());
      break;  // one per file is enough
    }
  }
  eval::carmen::CarmenLog log;
  for (const char* file : {"real/intel/intel.rebuilt.clf", "real/fr079/fr079.log"}) {
    for (const std::string& line : FirstLines(in.data_dir / file, 12)) {
      (void)eval::carmen::ParseCarmenLine(line, 0, {}, log);
    }
  }
  for (size_t i = 0; i < log.lasers.size() && i < 2; ++i) scans.push_back(log.lasers[i].scan);
  return scans;
}

void AddSickSeeds(SeedCorpus& corpus, const SeedInputs& in,
                  const std::vector<core::LaserScan>& real_scans) {
  AddRecordedStreams(corpus, in.data_dir / "sick");
  AddCapturedSegments(corpus, in.data_dir / "sick");
  AddEncodedTelegrams(corpus, real_scans);
  AddS300(corpus, real_scans);
}

void AddLogSeeds(SeedCorpus& corpus, const SeedInputs& in) {
  const std::vector<std::string> can =
      FirstLines(in.data_dir / "can/SOC_Manual_candump-2022-04-06_125818.log", 12);
  std::string real;
  for (const std::string& line : can) real += line;
  if (!real.empty()) corpus.Add("candump", "tesla_model3_12_lines", real);
  // Every syntax candump_log.h knows, as candump writes it.
  corpus.Add("candump", "syntax_variants",
             "(1649249898.730936) can0 243#00000000A0000400\n"
             "(1649249898.731167) vcan1 12345678#DEADBEEF\n"
             "(0000000001.000000) can0 123#R\n(1.5) can0 123#R4\n"
             "(2.25) can0 123##1112233445566778899AABBCC\n(3.0) can0 20000080#0000000000000000\n"
             "(4.0) can0 321#1122334455667788_C\n(5.0) can0 321#11.22.33 R\n"
             "# a comment\n\n");
  for (const char* file :
       {"real/intel/intel.rebuilt.clf", "real/intel/intel-lab.log", "real/fr079/fr079.log",
        "real/aces/aces-corrected.log.gz", "real/mit-killian/mit-killian.rebuilt.clf"}) {
    std::string text;
    for (const std::string& line : FirstLines(in.data_dir / file, 10)) text += line;
    if (!text.empty()) corpus.Add("carmen", fs::path(file).filename().string(), "# " + text);
  }
}

}  // namespace fleetmap::fuzz
