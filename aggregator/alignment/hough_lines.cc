#include "aggregator/alignment/hough_lines.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

namespace fleetmap::aggregator {

core::Status HoughOptions::Validate() const {
  if (!(rho_cells > 0)) return core::InvalidArgument("hough.rho_cells must be > 0");
  if (!(theta_step_rad > 0 && theta_step_rad <= M_PI / 8))
    return core::InvalidArgument("hough.theta_step_rad must be in (0, pi/8]");
  if (min_votes < 1) return core::InvalidArgument("hough.min_votes must be >= 1");
  if (!(min_length_cells >= 0)) return core::InvalidArgument("hough.min_length_cells must be >= 0");
  if (!(max_gap_cells >= 0)) return core::InvalidArgument("hough.max_gap_cells must be >= 0");
  return core::OkStatus();
}

core::Result<std::vector<LineSegment>> DetectHoughSegments(const BinaryImage& image,
                                                           const HoughOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<size_t>(image.width) * image.height) {
    return core::InvalidArgument("hough: picture size does not match its pixels");
  }
  std::vector<cv::Vec4i> found;
  try {
    // OpenCV reads the bytes without copying; HoughLinesP does not write them.
    const cv::Mat mat(image.height, image.width, CV_8UC1,
                      const_cast<uint8_t*>(image.pixels.data()));
    cv::HoughLinesP(mat, found, options.rho_cells, options.theta_step_rad, options.min_votes,
                    options.min_length_cells, options.max_gap_cells);
  } catch (const cv::Exception& e) {
    return core::InvalidArgument(std::string("hough: OpenCV failed: ") + e.what());
  }
  std::vector<LineSegment> segments;
  segments.reserve(found.size());
  for (const cv::Vec4i& l : found) {
    segments.push_back({{l[0] + 0.5, l[1] + 0.5}, {l[2] + 0.5, l[3] + 0.5}});
  }
  return segments;
}

}  // namespace fleetmap::aggregator
