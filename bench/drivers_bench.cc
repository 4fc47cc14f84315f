// Driver throughput: parsing of one SICK scan telegram (an 811-point TiM781S-like CoLa-B scan
// with DIST1 and RSSI1; a 541-point LMS111-like CoLa-A scan) and CANopen odometry decoding per
// CAN frame (SYNC and two position TPDOs per cycle).
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <vector>

#include "bench/figure_reporter.h"
#include "drivers/can/diff_drive_can_encoder.h"
#include "drivers/can/diff_drive_odometry.h"
#include "drivers/sick/cola_frame.h"
#include "drivers/sick/scan_telegram_codec.h"
#include "drivers/sick/telegram_splitter.h"

namespace fleetmap::bench {
namespace {

using drivers::sick::ColaProtocol;

std::string ScanPayload(ColaProtocol protocol, int points, bool rssi) {
  drivers::sick::ScanTelegram t;
  t.scan_frequency_centihz = points == 811 ? 1500 : 5000;
  for (const char* name : {"DIST1", "RSSI1"}) {
    if (std::string(name) == "RSSI1" && !rssi) break;
    drivers::sick::ScanChannel c;
    c.content = name;
    c.start_angle_1e4deg = -450000;
    c.angular_step_1e4deg = points == 811 ? 3333 : 5000;
    for (int i = 0; i < points; ++i) {
      c.values.push_back(static_cast<uint16_t>(800 + 3000 * (1 + std::sin(i * 0.05))));
    }
    t.channels16.push_back(c);
  }
  t.clock = drivers::sick::ScanClock{};
  return drivers::sick::EncodeScanTelegram(t, protocol);
}

void ParseLoop(benchmark::State& state, ColaProtocol protocol, const std::string& payload) {
  drivers::sick::ScanTelegram telegram;
  for (auto _ : state) {
    const core::Status s = drivers::sick::ParseScanTelegramInto(payload, protocol, telegram);
    if (!s.ok()) state.SkipWithError(s.ToString().c_str());
    benchmark::DoNotOptimize(telegram.channels16.data());
  }
}

void BM_ParseColaB811(benchmark::State& state) {
  ParseLoop(state, ColaProtocol::kColaB, ScanPayload(ColaProtocol::kColaB, 811, true));
}
BENCHMARK(BM_ParseColaB811)->Unit(benchmark::kMicrosecond);

void BM_ParseColaA541(benchmark::State& state) {
  ParseLoop(state, ColaProtocol::kColaA, ScanPayload(ColaProtocol::kColaA, 541, false));
}
BENCHMARK(BM_ParseColaA541)->Unit(benchmark::kMicrosecond);

// Framing included: the stream splitter cuts the telegram out of received bytes, then parses.
void BM_SplitAndParseColaB811(benchmark::State& state) {
  const std::string framed =
      drivers::sick::FrameColaB(ScanPayload(ColaProtocol::kColaB, 811, true));
  drivers::sick::TelegramSplitter splitter;
  drivers::sick::ScanTelegram telegram;
  for (auto _ : state) {
    splitter.Feed(framed);
    const auto payload = splitter.Next();
    benchmark::DoNotOptimize(
        drivers::sick::ParseScanTelegramInto(*payload, ColaProtocol::kColaB, telegram));
  }
}
BENCHMARK(BM_SplitAndParseColaB811)->Unit(benchmark::kMicrosecond);

void BM_DecodeCanFrame(benchmark::State& state) {
  drivers::can::DiffDriveCanOptions options;
  drivers::can::DiffDriveCanEncoder encoder(options);
  std::vector<drivers::can::CanFrame> frames;
  for (int i = 0; i < 1000; ++i) {
    core::OdometrySample s;
    s.stamp_s = i * 0.02;
    s.pose_in_odom = core::Pose2(0.01 * i, 0.0, 0.001 * i);
    for (const auto& f : encoder.Encode(s)) frames.push_back(f);
  }
  drivers::can::DiffDriveOdometry odometry(options);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(odometry.Decode(frames[i]));
    if (++i == frames.size()) i = 0;
  }
}
BENCHMARK(BM_DecodeCanFrame);

}  // namespace
}  // namespace fleetmap::bench

int main(int argc, char** argv) {
  using namespace fleetmap::bench;
  RecordFigure("sick.colab_811_bytes",
               double(ScanPayload(ColaProtocol::kColaB, 811, true).size() + 9), "B");
  RecordFigure("sick.colaa_541_bytes",
               double(ScanPayload(ColaProtocol::kColaA, 541, false).size() + 2), "B");
  TimeFigure("BM_ParseColaB811", "sick.parse_colab_811_us", "us");
  TimeFigure("BM_ParseColaA541", "sick.parse_colaa_541_us", "us");
  TimeFigure("BM_SplitAndParseColaB811", "sick.split_parse_colab_811_us", "us");
  TimeFigure("BM_DecodeCanFrame", "can.decode_frame_ns", "ns");
  return RunBenchmarksAndPrintFigures(argc, argv);
}
