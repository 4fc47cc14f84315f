#include "sim/sick/scan_source.h"

#include <cmath>

#include "drivers/sick/scan_conversion.h"
#include "drivers/sick/scan_telegram_codec.h"
#include "sim/sick/recording_reader.h"

namespace fleetmap::sim::sick {

RecordingScanSource::RecordingScanSource(std::vector<drivers::sick::ScanTelegram> scans, bool loop)
    : scans_(std::move(scans)), loop_(loop) {
  if (!scans_.empty() && scans_.front().scan_frequency_centihz > 0) {
    period_s_ = 100.0 / scans_.front().scan_frequency_centihz;
  }
}

core::Result<std::unique_ptr<RecordingScanSource>> RecordingScanSource::Load(
    const std::string& path, bool loop) {
  core::Result<Recording> recording = ReadRecording(path);
  if (!recording.ok()) return recording.status();
  std::vector<drivers::sick::ScanTelegram> scans;
  for (const RecordedTelegram& r : ScanTelegrams(*recording)) {
    core::Result<drivers::sick::ScanTelegram> t =
        drivers::sick::ParseScanTelegram(r.payload, r.protocol);
    if (!t.ok()) return t.status().WithContext(path);
    scans.push_back(std::move(t).value());
  }
  if (scans.empty()) return core::NotFound(path + ": no LMDscandata scans in the recording");
  return std::make_unique<RecordingScanSource>(std::move(scans), loop);
}

std::optional<drivers::sick::ScanTelegram> RecordingScanSource::Next() {
  if (next_ == scans_.size()) {
    if (!loop_ || scans_.empty()) return std::nullopt;
    next_ = 0;
  }
  return scans_[next_++];
}

SimulatorScanSource::SimulatorScanSource(std::unique_ptr<sim::World> world, size_t vehicle)
    : world_(std::move(world)),
      simulator_(world_.get()),
      vehicle_(vehicle),
      period_s_(world_->scenario().vehicles[vehicle].scanner.period_s()) {}

core::Result<std::unique_ptr<SimulatorScanSource>> SimulatorScanSource::Create(sim::World world,
                                                                               size_t vehicle) {
  if (vehicle >= world.scenario().vehicles.size()) {
    return core::InvalidArgument("vehicle " + std::to_string(vehicle) + " is not in " +
                                 world.scenario().name);
  }
  auto owned = std::make_unique<sim::World>(std::move(world));
  return std::unique_ptr<SimulatorScanSource>(new SimulatorScanSource(std::move(owned), vehicle));
}

std::optional<drivers::sick::ScanTelegram> SimulatorScanSource::Next() {
  while (std::optional<sim::SimEvent> event = simulator_.Next()) {
    const auto* scan = std::get_if<sim::ScanEvent>(&*event);
    if (scan == nullptr || scan->vehicle != vehicle_) continue;
    drivers::sick::ScanTelegram t = drivers::sick::FromLaserScan(scan->scan);
    t.serial_number = 0x0F1EE7 + static_cast<uint32_t>(vehicle_);
    t.telegram_counter = t.scan_counter = ++counter_;
    t.time_since_startup_us = static_cast<uint32_t>(std::llround(scan->scan.stamp_s * 1e6));
    t.time_of_transmission_us =
        t.time_since_startup_us + static_cast<uint32_t>(std::llround(period_s_ * 1e6));
    t.measurement_frequency_100hz =
        static_cast<uint32_t>(std::lround(scan->scan.size() / period_s_ / 100.0));
    return t;
  }
  return std::nullopt;
}

}  // namespace fleetmap::sim::sick
