#include "sim/route.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fleetmap::sim {
namespace {

TEST(RouteTest, DrivesTurnsAndStops) {
  RouteOptions o;
  o.speed_mps = 0.5;
  o.angular_speed_radps = 0.5;
  const Route route({{0, 0}, {2, 0}, {2, 1}}, o);
  // 4 s to the corner, pi/2 / 0.5 = 3.14 s turn, 2 s up.
  EXPECT_NEAR(route.period_s(), 4 + M_PI + 2, 1e-9);
  const RouteState mid = route.StateAt(2.0);
  EXPECT_NEAR(mid.pose.x_m, 1.0, 1e-9);
  EXPECT_NEAR(mid.v_mps, 0.5, 1e-9);
  const RouteState turning = route.StateAt(4.0 + M_PI / 2);
  EXPECT_NEAR(turning.pose.theta_rad, M_PI / 4, 1e-9);
  EXPECT_NEAR(turning.omega_radps, 0.5, 1e-9);
  const RouteState end = route.StateAt(100.0);
  EXPECT_NEAR(end.pose.x_m, 2.0, 1e-9);
  EXPECT_NEAR(end.pose.y_m, 1.0, 1e-9);
  EXPECT_EQ(end.v_mps, 0.0);
}

TEST(RouteTest, StandsStillAtEachWaypointForItsDwell) {
  RouteOptions o;
  o.speed_mps = 1.0;
  o.dwell_s = 3.0;
  const Route route({{0, 0}, {2, 0}, {2, 2}}, o);
  // 2 s to the corner, 3 s standing, the turn, 2 s up, 3 s standing at the end.
  EXPECT_NEAR(route.period_s(), 2 + 3 + M_PI / 2 / 0.5 + 2 + 3, 1e-9);
  for (double t : {2.1, 3.5, 4.9}) {
    const RouteState standing = route.StateAt(t);
    EXPECT_NEAR(standing.pose.x_m, 2.0, 1e-9) << t;
    EXPECT_EQ(standing.v_mps, 0.0) << t;
    EXPECT_EQ(standing.omega_radps, 0.0) << t;
  }
  EXPECT_GT(route.StateAt(5.1).omega_radps, 0.0);
}

TEST(RouteTest, LoopReturnsToTheStartPose) {
  RouteOptions o;
  o.loop = true;
  const Route route({{0, 0}, {4, 0}, {4, 3}}, o);
  const RouteState a = route.StateAt(0.5), b = route.StateAt(0.5 + route.period_s());
  EXPECT_NEAR(a.pose.x_m, b.pose.x_m, 1e-9);
  EXPECT_NEAR(a.pose.theta_rad, b.pose.theta_rad, 1e-9);
}

TEST(RouteTest, WaitsUntilItsStartTime) {
  RouteOptions o;
  o.start_s = 10;
  const Route route({{1, 1}, {3, 1}}, o);
  EXPECT_EQ(route.StateAt(5.0).pose.x_m, 1.0);
  EXPECT_NEAR(route.StateAt(12.0).pose.x_m, 2.0, 1e-9);
}

}  // namespace
}  // namespace fleetmap::sim
