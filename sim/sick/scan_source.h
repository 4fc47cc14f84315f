// Where the emulated scanner's scans come from: a recording of a real scanner (replayed,
// optionally in a loop) or the simulator (one vehicle's scanner in a simulated world).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"
#include "drivers/sick/scan_telegram.h"
#include "sim/simulator.h"

namespace fleetmap::sim::sick {

class ScanSource {
 public:
  virtual ~ScanSource() = default;
  // The next scan; nothing once the source is exhausted.
  virtual std::optional<drivers::sick::ScanTelegram> Next() = 0;
  // Time between scans, seconds.
  virtual double period_s() const = 0;
};

// Replays parsed telegrams in order, forever if `loop`.
class RecordingScanSource : public ScanSource {
 public:
  RecordingScanSource(std::vector<drivers::sick::ScanTelegram> scans, bool loop);
  // Reads every scan of a recording file (recording_reader.h).
  static core::Result<std::unique_ptr<RecordingScanSource>> Load(const std::string& path,
                                                                 bool loop);
  std::optional<drivers::sick::ScanTelegram> Next() override;
  double period_s() const override { return period_s_; }
  size_t size() const { return scans_.size(); }

 private:
  std::vector<drivers::sick::ScanTelegram> scans_;
  bool loop_;
  size_t next_ = 0;
  double period_s_ = 0.1;
};

// One vehicle's scans from the simulator, as telegrams of a scanner with the simulated
// model's geometry; device time starts at power-up = simulation time 0.
class SimulatorScanSource : public ScanSource {
 public:
  static core::Result<std::unique_ptr<SimulatorScanSource>> Create(sim::World world,
                                                                   size_t vehicle);
  std::optional<drivers::sick::ScanTelegram> Next() override;
  double period_s() const override { return period_s_; }

 private:
  SimulatorScanSource(std::unique_ptr<sim::World> world, size_t vehicle);
  std::unique_ptr<sim::World> world_;
  sim::Simulator simulator_;
  size_t vehicle_;
  double period_s_;
  uint16_t counter_ = 0;
};

}  // namespace fleetmap::sim::sick
