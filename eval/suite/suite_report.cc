#include "eval/suite/suite_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "core/image/map_render.h"

namespace fleetmap::eval::suite {
namespace {

int GroupRank(const WorldOutcome& o) {
  switch (o.world.source) {
    case WorldSource::kGenerated:
      return 0;
    case WorldSource::kPublic:
      return 1;
    case WorldSource::kLivingLab:
      return 2;
  }
  return 3;
}

std::string Cell(double v, const char* format = "%.3f") {
  if (!std::isfinite(v)) return "-";
  char text[32];
  std::snprintf(text, sizeof(text), format, v);
  return text;
}

std::string Where(const WorldOutcome& o) {
  char text[96];
  const double turn_deg = o.world.source == WorldSource::kGenerated
                              ? o.world.generated.render.rotation_rad * 180.0 / M_PI
                              : NAN;
  std::snprintf(
      text, sizeof(text), "%.3f m, %.0f x %.0f m%s", o.prepared.resolution_m, o.prepared.width_m,
      o.prepared.height_m,
      std::isfinite(turn_deg) ? (", turned " + Cell(turn_deg, "%.0f") + " deg").c_str() : "");
  return text;
}

std::string ScoreColumns(const std::optional<WorldScore>& s, const std::string& error) {
  if (!s)
    return "| " + (error.empty() ? std::string("not run") : "failed: " + error) + " | | | | | | |";
  return "| " + Cell(s->changed_f1) + " | " + Cell(s->added_recall) + " | " +
         Cell(s->removed_recall) + " | " + std::to_string(s->static_erased) + " | " +
         std::to_string(s->actor_mapped) + " | " + Cell(s->align_trans_p95_cells, "%.2f") + " | " +
         std::to_string(s->merges_rejected) + "/" +
         std::to_string(s->merges_accepted + s->merges_rejected) + " (" + Cell(s->run_s, "%.0f") +
         " s) |";
}

}  // namespace

std::vector<const WorldOutcome*> InReportOrder(const std::vector<WorldOutcome>& outcomes) {
  std::vector<const WorldOutcome*> order;
  for (const WorldOutcome& o : outcomes) order.push_back(&o);
  std::stable_sort(order.begin(), order.end(), [](const WorldOutcome* a, const WorldOutcome* b) {
    if (GroupRank(*a) != GroupRank(*b)) return GroupRank(*a) < GroupRank(*b);
    if (a->world.group != b->world.group) return a->world.group < b->world.group;
    return a->prepared.resolution_m < b->prepared.resolution_m;
  });
  return order;
}

std::string SuiteMarkdown(const std::vector<WorldOutcome>& outcomes,
                          const std::vector<Figure>& figures) {
  std::string md =
      "# World suite\n\n## Aggregate\n\n| figure | value | unit |\n| --- | --- | --- |\n";
  for (const Figure& f : figures)
    if (f.name.rfind("suite.world.", 0) != 0)
      md += "| " + f.name + " | " + Cell(f.value, "%.4g") + " | " + f.unit + " |\n";
  for (const char* pipeline : {"agents", "truthmaps"}) {
    const bool agents = std::string(pipeline) == "agents";
    md += std::string("\n## Per world: pipeline ") + pipeline +
          "\n\n| world | group | map | changed F1 | added recall | removed recall | static "
          "erased | actor mapped | align p95 (cells) | rejected (run) |\n"
          "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    for (const WorldOutcome* o : InReportOrder(outcomes)) {
      md += "| " + o->world.name + " | " + o->world.group + " | ";
      if (!o->unusable.empty()) {
        md += "unusable: " + o->unusable + " | | | | | | | |\n";
        continue;
      }
      md += Where(*o) + (o->prepared.fitted.empty() ? "" : " (" + o->prepared.fitted + ")") + " ";
      md += agents ? ScoreColumns(o->agents, o->agents_error)
                   : ScoreColumns(o->truthmaps, o->truthmaps_error);
      md += "\n";
    }
  }
  md +=
      "\nThe LivingLab hall is beside the suite, in no aggregate. Unusable worlds are in no "
      "aggregate either.\n";
  return md;
}

core::Status WriteSuitePng(const std::vector<WorldOutcome>& outcomes, const std::string& path) {
  const std::vector<const WorldOutcome*> order = InReportOrder(outcomes);
  constexpr int kRow = 18, kLabel = 330, kBar = 500, kTop = 40, kMargin = 10;
  int groups = 0;
  for (size_t i = 0; i < order.size(); ++i)
    groups += i == 0 || order[i]->world.group != order[i - 1]->world.group;
  const int height = kTop + kRow * (static_cast<int>(order.size()) + groups) + 40;
  core::BgrImage picture;  // drawn through a cv::Mat over its pixels, written by core::WritePng
  picture.width = kLabel + kBar + 2 * kMargin;
  picture.height = height;
  picture.pixels.assign(static_cast<size_t>(picture.width) * height * 3, 255);
  cv::Mat img(picture.height, picture.width, CV_8UC3, picture.pixels.data());
  const auto x_of = [&](double f1) { return kLabel + static_cast<int>(std::lround(f1 * kBar)); };
  const auto text = [&](const std::string& s, int x, int y, const cv::Scalar& colour) {
    cv::putText(img, s, {x, y}, cv::FONT_HERSHEY_SIMPLEX, 0.4, colour, 1, cv::LINE_AA);
  };
  text("changed-cell F1 per world: bar = agents, black tick = truthmaps; lines at 0.92, 0.97",
       kMargin, 16, {0, 0, 0});
  int y = kTop;
  for (size_t i = 0; i < order.size(); ++i) {
    const WorldOutcome& o = *order[i];
    if (i == 0 || o.world.group != order[i - 1]->world.group) {
      text(o.world.group, kMargin, y + 13, {120, 60, 0});
      y += kRow;
    }
    text(o.world.name + "  " + Cell(o.prepared.resolution_m, "%.3f") + " m", kMargin + 12, y + 13,
         {0, 0, 0});
    if (!o.unusable.empty()) {
      text("unusable: " + o.unusable.substr(0, 70), kLabel, y + 13, {0, 0, 200});
    } else {
      if (o.agents)
        cv::rectangle(img, {kLabel, y + 3},
                      {x_of(std::clamp(o.agents->changed_f1, 0.0, 1.0)), y + kRow - 3},
                      {200, 140, 40}, cv::FILLED);
      if (o.truthmaps) {
        const int x = x_of(std::clamp(o.truthmaps->changed_f1, 0.0, 1.0));
        cv::line(img, {x, y + 1}, {x, y + kRow - 1}, {0, 0, 0}, 2);
      }
      if (!o.agents && !o.truthmaps) text("no score", kLabel, y + 13, {0, 0, 200});
    }
    y += kRow;
  }
  for (double goal : {0.92, 0.97})
    cv::line(img, {x_of(goal), kTop}, {x_of(goal), y}, {0, 0, 220}, 1);
  for (int tick = 0; tick <= 10; ++tick) {
    const int x = x_of(tick / 10.0);
    cv::line(img, {x, y}, {x, y + 5}, {0, 0, 0}, 1);
    text(Cell(tick / 10.0, "%.1f"), x - 8, y + 20, {0, 0, 0});
  }
  return core::WritePng(picture, path);
}

}  // namespace fleetmap::eval::suite
