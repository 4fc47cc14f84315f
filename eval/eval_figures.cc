#include "eval/eval_figures.h"

#include <algorithm>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/io/file_io.h"

namespace fleetmap::eval {
namespace {

const cv::Scalar kPalette[] = {{40, 40, 220}, {200, 120, 0}, {0, 160, 0},
                               {180, 0, 180}, {0, 140, 255}, {120, 120, 0}};

core::Status SaveMat(const cv::Mat& image, const std::string& path) {
  std::vector<uint8_t> png;
  try {
    if (!cv::imencode(".png", image, png)) return core::IoError(path + ": PNG encoding failed");
  } catch (const cv::Exception& e) {
    return core::IoError(path + ": " + e.what());
  }
  return core::WriteFileAtomically(
      path, std::string_view(reinterpret_cast<char*>(png.data()), png.size()));
}

// The map as a picture, row 0 of the grid at the bottom, `scale` pixels per cell.
cv::Mat MapImage(const core::OccupancyGrid& grid, int scale) {
  const auto& g = grid.geometry();
  cv::Mat img(g.height(), g.width(), CV_8UC3);
  const core::TriStateClassifier classify;
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      const core::CellState s = classify(grid.log_odds({x, y}));
      const uint8_t v = s == core::CellState::kOccupied ? 60
                        : s == core::CellState::kFree   ? 255
                                                        : 200;
      img.at<cv::Vec3b>(g.height() - 1 - y, x) = {v, v, v};
    }
  }
  cv::resize(img, img, cv::Size(), scale, scale, cv::INTER_NEAREST);
  return img;
}

cv::Point ToPixel(const core::GridGeometry& g, const Eigen::Vector2d& world, int scale) {
  const Eigen::Vector2d c = g.WorldToGrid(world);
  return {int(c.x() * scale), int((g.height() - c.y()) * scale)};
}

void Paint(cv::Mat& img, int height, int64_t index, int width, int scale, const cv::Vec3b& color) {
  const int x = int(index % width), y = int(index / width);
  cv::rectangle(img, cv::Rect(x * scale, (height - 1 - y) * scale, scale, scale),
                cv::Scalar(color[0], color[1], color[2]), cv::FILLED);
}

// The picture with a white band below it holding `text`, so no legend hides the map; the
// text wraps (at runs of three spaces, between entries, where it can) to the picture's width.
cv::Mat WithLegend(const cv::Mat& img, const std::string& text) {
  constexpr double kScale = 0.5;
  constexpr int kLine = 20;
  std::vector<std::string> entries;
  for (size_t from = 0; from < text.size();) {
    const size_t gap = text.find("   ", from);
    entries.push_back(text.substr(from, gap == std::string::npos ? std::string::npos : gap - from));
    from = gap == std::string::npos ? text.size() : text.find_first_not_of(' ', gap);
  }
  std::vector<std::string> lines(1);
  for (const std::string& e : entries) {
    const std::string longer = lines.back().empty() ? e : lines.back() + "   " + e;
    int baseline = 0;
    const int width = cv::getTextSize(longer, cv::FONT_HERSHEY_SIMPLEX, kScale, 1, &baseline).width;
    if (width + 16 > img.cols && !lines.back().empty()) {
      lines.push_back(e);
    } else {
      lines.back() = longer;
    }
  }
  cv::Mat out(img.rows + 8 + kLine * static_cast<int>(lines.size()), img.cols, CV_8UC3,
              cv::Scalar(255, 255, 255));
  img.copyTo(out(cv::Rect(0, 0, img.cols, img.rows)));
  for (size_t i = 0; i < lines.size(); ++i)
    cv::putText(out, lines[i], {8, img.rows + 19 + kLine * static_cast<int>(i)},
                cv::FONT_HERSHEY_SIMPLEX, kScale, {0, 0, 0}, 1, cv::LINE_AA);
  return out;
}

cv::Vec3b ColourOf(OverlayClass k) {  // BGR
  switch (k) {
    case OverlayClass::kAddedOk:
      return {0, 180, 0};  // green
    case OverlayClass::kFalseAdded:
      return {0, 0, 230};  // red
    case OverlayClass::kMissed:
      return {230, 0, 0};  // blue
    case OverlayClass::kMissedSeenFree:
      return {255, 255, 255};  // white
    case OverlayClass::kRemovedOk:
      return {220, 200, 0};  // cyan
    case OverlayClass::kFalseRemoval:
      return {220, 0, 220};  // magenta
    case OverlayClass::kMissedRemoval:
      return {0, 140, 255};  // orange
    case OverlayClass::kWallErased:
      return {0, 220, 255};  // yellow
    case OverlayClass::kActorMapped:
      return {200, 0, 120};  // purple
    case OverlayClass::kNone:
      break;
  }
  return {0, 0, 0};
}

}  // namespace

OverlayClass ClassifyOverlayCell(const OverlayCell& c) {
  if (c.is_static) return c.occupied ? OverlayClass::kNone : OverlayClass::kWallErased;
  if (c.actor_swept && !c.true_added && (c.occupied || c.ever_occupied))
    return OverlayClass::kActorMapped;
  if (c.occupied) return c.true_added ? OverlayClass::kAddedOk : OverlayClass::kFalseAdded;
  if (c.true_added) return c.seen_free_near ? OverlayClass::kMissedSeenFree : OverlayClass::kMissed;
  if (c.ever_occupied)
    return c.true_removed ? OverlayClass::kRemovedOk : OverlayClass::kFalseRemoval;
  if (c.true_removed) return OverlayClass::kMissedRemoval;
  return OverlayClass::kNone;
}

core::Status WriteOverlayPng(const sim::World& world, const sim::ObservationLog& observations,
                             const RunRecord& run, const std::string& path) {
  const auto& g = world.geometry();
  const int scale = 2;
  cv::Mat img = MapImage(run.final_map, scale);
  const core::TriStateClassifier classify;
  const std::vector<uint8_t> swept = ActorSweptCells(world, 0.05);
  const std::vector<uint8_t> seen_free = NearSeenFreeDrops(run, g);
  for (int64_t i = 0; i < g.num_cells(); ++i) {
    OverlayCell c;
    c.is_static = classify(world.static_map().cells()[i]) == core::CellState::kOccupied;
    c.occupied = classify(run.final_map.cells()[i]) == core::CellState::kOccupied;
    c.ever_occupied = !run.ever_occupied.empty() && run.ever_occupied[i];
    const sim::CellObservations* o = observations.Cell(i);
    const core::CellState truth = o ? o->LastState() : core::CellState::kUnknown;
    c.true_added = truth == core::CellState::kOccupied && !c.is_static;
    c.true_removed = o && o->ever_hit && truth == core::CellState::kFree;
    c.actor_swept = swept[i];
    c.seen_free_near = !seen_free.empty() && seen_free[i];
    const OverlayClass k = ClassifyOverlayCell(c);
    if (k != OverlayClass::kNone) Paint(img, g.height(), i, g.width(), scale, ColourOf(k));
  }
  return SaveMat(WithLegend(img,
                            "green: added ok   red: false   blue: missed   white: missed, seen "
                            "free   cyan: removed ok   "
                            "magenta: false removal   orange: missed removal   yellow: wall "
                            "erased   purple: actor mapped at any time"),
                 path);
}

core::Status WriteDivergencePng(const RunRecord& run, const std::string& path) {
  std::map<std::string, std::vector<const DivergenceSample*>> by_vehicle;
  double t_max = 1.0;
  for (const DivergenceSample& s : run.divergence) {
    by_vehicle[s.vehicle_id].push_back(&s);
    t_max = std::max(t_max, s.t_s);
  }
  const int panel_h = 220, width = 1200, margin = 40;
  const int panels = std::max<int>(1, int(by_vehicle.size()));
  cv::Mat img(panels * panel_h, width, CV_8UC3, cv::Scalar(255, 255, 255));
  if (by_vehicle.empty()) {
    cv::putText(img, "no divergence samples in this run (pipeline: " + run.pipeline + ")",
                {margin, panel_h / 2}, cv::FONT_HERSHEY_SIMPLEX, 0.6, {0, 0, 0}, 1, cv::LINE_AA);
  }
  int p = 0;
  for (const auto& [vehicle, samples] : by_vehicle) {
    const int top = p++ * panel_h + 20, bottom = top + panel_h - 50;
    auto px = [&](double t, double v) {
      return cv::Point(margin + int((width - 2 * margin) * t / t_max),
                       bottom - int((bottom - top) * std::clamp(v, 0.0, 1.0)));
    };
    cv::rectangle(img, px(0, 1), px(t_max, 0), {180, 180, 180});
    for (size_t i = 0; i < samples.size(); ++i) {
      if (samples[i]->building)
        cv::line(img, px(samples[i]->t_s, 0), px(samples[i]->t_s, 1), {230, 230, 255});
    }
    const cv::Scalar colors[4] = {{0, 0, 220}, {150, 150, 150}, {200, 120, 0}, {0, 150, 0}};
    for (size_t i = 1; i < samples.size(); ++i) {
      const DivergenceSample &a = *samples[i - 1], &b = *samples[i];
      const double va[4] = {a.d, a.w_avg, a.w_fast, a.w_slow},
                   vb[4] = {b.d, b.w_avg, b.w_fast, b.w_slow};
      for (int k = 3; k >= 0; --k)
        cv::line(img, px(a.t_s, va[k]), px(b.t_s, vb[k]), colors[k], 1, cv::LINE_AA);
    }
    cv::putText(img,
                vehicle +
                    ": d (red), w_avg (grey), w_fast (blue), w_slow (green); shaded: building a "
                    "temporary map; 0.." +
                    std::to_string(int(t_max)) + " s",
                {margin, top - 4}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0}, 1, cv::LINE_AA);
  }
  return SaveMat(img, path);
}

core::Status WritePathsPng(const sim::World& world, const RunRecord& run, const std::string& path) {
  const auto& g = world.geometry();
  const int scale = 2;
  cv::Mat img = MapImage(run.final_map, scale);
  const auto& vehicles = world.scenario().vehicles;
  for (size_t v = 0; v < vehicles.size(); ++v) {
    cv::Point last = ToPixel(g, world.VehicleStateAt(v, 0).pose.translation(), scale);
    for (double t = 0.5; t <= world.scenario().duration_s; t += 0.5) {
      const cv::Point p = ToPixel(g, world.VehicleStateAt(v, t).pose.translation(), scale);
      cv::line(img, last, p, {150, 150, 150}, 3, cv::LINE_AA);
      last = p;
    }
  }
  std::map<std::string, cv::Point> last_estimate;
  std::map<std::string, size_t> color_of;
  for (const PoseSample& s : run.poses) {
    const size_t color = color_of.emplace(s.vehicle_id, color_of.size()).first->second % 6;
    const cv::Point p = ToPixel(g, s.estimated.translation(), scale);
    auto it = last_estimate.find(s.vehicle_id);
    if (it != last_estimate.end()) cv::line(img, it->second, p, kPalette[color], 1, cv::LINE_AA);
    last_estimate[s.vehicle_id] = p;
  }
  cv::Mat out = WithLegend(img, "grey: true paths; estimated:");
  int x = 270;
  for (const auto& [id, color] : color_of) {
    cv::putText(out, id, {x, img.rows + 19}, cv::FONT_HERSHEY_SIMPLEX, 0.5, kPalette[color % 6], 1,
                cv::LINE_AA);
    x += 12 * static_cast<int>(id.size()) + 20;
  }
  return SaveMat(out, path);
}

}  // namespace fleetmap::eval
