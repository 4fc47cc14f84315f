// A building as drawn by an architect, in metres of the building's own frame (x along its
// length, y across, origin at the outer corner): walls as thick polylines and solid
// footprints (racks, columns, furniture, machines). The styles (building_styles.h) draw one;
// slam_rendering.h turns it into a map that looks like SLAM made it.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace fleetmap::sim::worldgen {

using Polyline = std::vector<Eigen::Vector2d>;

struct Wall {
  Polyline points_m;  // at least two points
  double thickness_m = 0.2;
  bool outer = false;  // part of the building's envelope (never given SLAM gaps: see rendering)
};

struct Solid {
  std::string kind;    // "rack", "column", "desk", "bed", "machine", "pallet_block", ...
  Polyline polygon_m;  // closed implicitly, at least three points
};

struct FloorPlan {
  std::string style;
  double length_m = 0.0;  // extent of the building frame along x and y
  double width_m = 0.0;
  std::vector<Wall> walls;
  std::vector<Solid> solids;

  void AddWall(Polyline points_m, double thickness_m, bool outer = false);
  // A straight wall from a to b with door-like openings: each opening is (distance of its
  // centre from a, width), in metres; openings that do not fit are left out.
  void AddWallWithOpenings(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double thickness_m,
                           std::vector<std::pair<double, double>> openings);
  // An axis-aligned box [x0, x1] x [y0, y1].
  void AddBox(const std::string& kind, double x0, double y0, double x1, double y1);
  // A box of size (sx, sy) centred at c, turned by yaw.
  void AddTurnedBox(const std::string& kind, const Eigen::Vector2d& c, double sx, double sy,
                    double yaw_rad);
  // A round column or table as a polygon of 16 sides.
  void AddDisc(const std::string& kind, const Eigen::Vector2d& c, double radius_m);
  // The four outer walls of the rectangle [0, length] x [0, width].
  void AddRectangularEnvelope(double thickness_m);
};

// Points along an arc of radius r about c from angle a0 to a1 (radians), about every
// `step_m` metres.
Polyline Arc(const Eigen::Vector2d& c, double r, double a0, double a1, double step_m = 0.5);

}  // namespace fleetmap::sim::worldgen
