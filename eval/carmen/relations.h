// The SLAM benchmark metric of Kümmerle et al., "On measuring the accuracy of SLAM algorithms"
// (Autonomous Robots 27(4), 2009): for every relation (t1, t2, delta*) between two scan
// times, the error of the estimated relative motion delta = x(t1)^-1 x(t2) against delta*;
// reported as mean and standard deviation of the absolute translational and rotational errors.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "core/result.h"

namespace fleetmap::eval::carmen {

struct Relation {
  double t1_s = 0.0, t2_s = 0.0;
  core::Pose2 delta;  // pose at t2 in the frame of the pose at t1
};

// Lines "t1 t2 x y z roll pitch yaw" (z, roll and pitch are 0 in 2D logs).
core::Result<std::vector<Relation>> ReadRelations(const std::string& path);

struct TimedPose {
  double stamp_s = 0.0;
  core::Pose2 pose;
};

// Another system's trajectory, lines "t x y theta" ('#' starts a comment line), sorted by
// time as ScoreRelations wants it. InvalidArgument names a malformed line.
core::Result<std::vector<TimedPose>> ReadTrajectory(const std::string& path);

// The pose whose time stamp is nearest `t`, if within 1 ms; nullptr otherwise. `trajectory`
// sorted by time.
const TimedPose* NearestInTime(const std::vector<TimedPose>& trajectory, double t);

// Writes `trajectory` as ReadTrajectory reads it (a comment line, then `t x y theta`, enough
// digits to round-trip to a micrometre and a microsecond), atomically (core::WriteFileAtomically):
// a folder that is not there or a full disk is an IoError naming the path, and no half file.
core::Status WriteTrajectory(const std::string& path, const std::vector<TimedPose>& trajectory);

struct RelationErrors {
  int used = 0;     // relations scored
  int missing = 0;  // relations within the span whose time stamps are not in the trajectory
  double trans_mean_m = 0.0, trans_std_m = 0.0;  // over the `used` relations only
  double rot_mean_deg = 0.0, rot_std_deg = 0.0;

  // Share of the relations within the span that could not be scored; NaN when there were none.
  double missing_share() const;
};

// Scores the relations spanning at most `max_span_s` (|t2 - t1|). Trajectory poses are
// looked up by time stamp: the nearest one, within 1 ms; `trajectory` must be sorted by time.
RelationErrors ScoreRelations(const std::vector<Relation>& relations,
                              const std::vector<TimedPose>& trajectory,
                              double max_span_s = std::numeric_limits<double>::infinity());

// OK when `errors` scored at least one relation. Otherwise its means are over nothing and no
// figure may be read from them: NotFound with how many relations there were, how many were
// within `max_span_s`, and the time ranges of the relations and of the trajectory (a log
// whose stamps are not those its relations were made from, e.g. rewritten ones, matches none).
core::Status CheckScored(const RelationErrors& errors, const std::vector<Relation>& relations,
                         const std::vector<TimedPose>& trajectory,
                         double max_span_s = std::numeric_limits<double>::infinity());

}  // namespace fleetmap::eval::carmen
