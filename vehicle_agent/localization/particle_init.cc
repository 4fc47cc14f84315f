#include "vehicle_agent/localization/particle_init.h"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace fleetmap::vehicle_agent {

ParticleSet SampleAroundPose(const core::Pose2& mean, const Eigen::Matrix3d& covariance, int count,
                             std::mt19937& rng) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  const Eigen::Matrix3d root =
      eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal();
  std::normal_distribution<double> normal(0.0, 1.0);
  ParticleSet particles(static_cast<size_t>(std::max(count, 0)));
  for (Particle& p : particles) {
    const Eigen::Vector3d d = root * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    p.pose = core::Pose2(mean.x_m + d.x(), mean.y_m + d.y(),
                         core::NormalizeAngle(mean.theta_rad + d.z()));
    p.weight = 1.0 / static_cast<double>(particles.size());
  }
  return particles;
}

ParticleSet SampleFreeSpace(const core::OccupancyGrid& map, int count, std::mt19937& rng) {
  const core::GridGeometry& g = map.geometry();
  const core::TriStateClassifier classify;
  std::vector<int64_t> free_cells;
  for (size_t i = 0; i < map.cells().size(); ++i)
    if (classify(map.cells()[i]) == core::CellState::kFree) free_cells.push_back(int64_t(i));
  ParticleSet particles;
  if (free_cells.empty() || count <= 0) return particles;
  std::uniform_int_distribution<size_t> pick(0, free_cells.size() - 1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < count; ++k) {
    const int64_t cell = free_cells[pick(rng)];
    const double gx = double(cell % g.width()) + unit(rng),
                 gy = double(cell / g.width()) + unit(rng);
    const Eigen::Vector2d world = g.origin().Apply(g.resolution_m() * Eigen::Vector2d(gx, gy));
    particles.push_back(
        {core::Pose2(world.x(), world.y(), M_PI * (2.0 * unit(rng) - 1.0)), 1.0 / count});
  }
  return particles;
}

}  // namespace fleetmap::vehicle_agent
