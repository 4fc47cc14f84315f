// fleetmap-bench-carmen2rawlog: a CARMEN log as an MRPT rawlog for MRPT's icp-slam, with every
// action and observation stamped with the log's own time (Debian's MRPT 2.5.8 carmen2rawlog
// stamps them with the conversion time, so icp-slam's pose extrapolation fails and its path
// never moves). Bench-only: built when MRPT's development packages are found, never part of
// the product (docs/performance.md).
//
// The log is read with the same reader fleetmap-carmen-eval uses, so both see the same scans
// and the same odometry: each step is one laser record, an odometry increment (the record's
// odometry pose relative to the previous record's) and the scan, with the laser's mounting
// from the log. Also writes STAMPS: one line per step, the record's time stamp, to pair
// icp-slam's log_estimated_path.txt (one pose per step) with the benchmark relations.
#include <mrpt/core/Clock.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <string>

#include "core/command_line.h"
#include "eval/carmen/carmen_log.h"

namespace {

using namespace fleetmap;

constexpr char kDescription[] =
    "Writes the CARMEN log LOG as an MRPT rawlog (actions and sensory frames, gzip) with the\n"
    "log's time stamps, and STAMPS: the time stamp of each step, one a line.";

mrpt::poses::CPose2D ToMrpt(const core::Pose2& p) {
  return mrpt::poses::CPose2D(p.x_m, p.y_m, p.theta_rad);
}

// Beam i of `scan` is at angle_min + i * increment; MRPT spaces its beams evenly over
// `aperture` centred on the sensor's heading, so the heading carries the offset.
mrpt::obs::CObservation2DRangeScan::Ptr ToMrpt(const eval::carmen::LaserRecord& r) {
  const core::LaserScan& scan = r.scan;
  auto obs = std::make_shared<mrpt::obs::CObservation2DRangeScan>();
  obs->sensorLabel = "LASER";
  obs->timestamp = mrpt::Clock::fromDouble(r.stamp_s);
  const size_t n = scan.size();
  const double span = scan.angle_increment_rad * static_cast<double>(n - 1);
  obs->aperture = static_cast<float>(std::abs(span));
  obs->rightToLeft = scan.angle_increment_rad > 0;
  obs->maxRange = static_cast<float>(scan.range_max_m);
  const core::Pose2& m = r.laser_in_base;
  obs->sensorPose =
      mrpt::poses::CPose3D(m.x_m, m.y_m, 0.0, m.theta_rad + scan.angle_min_rad + span / 2, 0, 0);
  obs->resizeScan(n);
  for (size_t i = 0; i < n; ++i) {
    const bool valid = scan.IsValidReturn(i);
    obs->setScanRange(i, valid ? scan.ranges_m[i] : obs->maxRange);
    obs->setScanRangeValidity(i, valid);
  }
  return obs;
}

}  // namespace

int main(int argc, char** argv) {
  std::string log_path, rawlog_path, stamps_path;
  CLI::App app(kDescription, "fleetmap-bench-carmen2rawlog");
  core::AddVersionFlag(app);
  app.add_option("LOG", log_path, "the CARMEN log")->required();
  app.add_option("RAWLOG", rawlog_path, "the MRPT rawlog to write")->required();
  app.add_option("STAMPS", stamps_path, "the time stamps to write")->required();
  if (const auto exit_status = core::ParseCommandLine(app, argc, argv)) return *exit_status;
  auto log = eval::carmen::ReadCarmenLog(log_path);
  if (!log.ok())
    return std::fprintf(stderr, "carmen2rawlog: %s\n", log.status().ToString().c_str()), 1;
  FILE* stamps = std::fopen(stamps_path.c_str(), "w");
  if (!stamps)
    return std::fprintf(stderr, "carmen2rawlog: %s: cannot write\n", stamps_path.c_str()), 1;
  try {
    mrpt::io::CFileGZOutputStream out(rawlog_path);
    auto archive = mrpt::serialization::archiveFrom(out);
    mrpt::obs::CActionRobotMovement2D::TMotionModelOptions motion;  // MRPT's defaults
    for (size_t i = 0; i < log->lasers.size(); ++i) {
      const eval::carmen::LaserRecord& r = log->lasers[i];
      const core::Pose2 delta =
          i == 0 ? core::Pose2() : core::Between(log->lasers[i - 1].odom_pose, r.odom_pose);
      mrpt::obs::CActionRobotMovement2D move;
      move.computeFromOdometry(ToMrpt(delta), motion);
      move.timestamp = mrpt::Clock::fromDouble(r.stamp_s);
      mrpt::obs::CActionCollection actions;
      actions.insert(move);
      mrpt::obs::CSensoryFrame frame;
      frame.insert(ToMrpt(r));
      archive << actions << frame;
      std::fprintf(stamps, "%.6f\n", r.stamp_s);
    }
  } catch (const std::exception& e) {
    std::fclose(stamps);
    return std::fprintf(stderr, "carmen2rawlog: %s\n", e.what()), 1;
  }
  std::fclose(stamps);
  std::fprintf(stderr, "carmen2rawlog: %s: %zu steps\n", rawlog_path.c_str(), log->lasers.size());
  return 0;
}
