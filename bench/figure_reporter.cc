#include "bench/figure_reporter.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <vector>

namespace fleetmap::bench {
namespace {

struct Figure {
  std::string name;
  double value;
  std::string unit;
};

struct TimeRequest {
  std::string figure;
  std::string unit;
  double rate_numerator = 0.0;  // > 0: report numerator / seconds instead of the time
};

// Figures are collected by the benchmark program's registration code and its benchmarks;
// one program, one run, so plain function-local statics are enough.
std::vector<Figure>& Figures() {
  static std::vector<Figure> figures;
  return figures;
}
std::map<std::string, TimeRequest>& TimeRequests() {
  static std::map<std::string, TimeRequest> requests;
  return requests;
}

double SecondsPer(const std::string& unit) {
  if (unit == "ns") return 1e-9;
  if (unit == "us") return 1e-6;
  if (unit == "ms") return 1e-3;
  return 1.0;
}

// Passes everything to the console and keeps the time of each requested benchmark.
class FigureReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      if (run.error_occurred) continue;
      // With repetitions, prefer the median aggregate; otherwise the single run.
      const bool aggregate = run.run_type == Run::RT_Aggregate;
      if (aggregate && run.aggregate_name != "median") continue;
      auto it = TimeRequests().find(run.run_name.str());
      if (it == TimeRequests().end()) continue;
      const double seconds = run.GetAdjustedRealTime() * SecondsPer(TimeUnitName(run.time_unit));
      const TimeRequest& req = it->second;
      const double value =
          req.rate_numerator > 0 ? req.rate_numerator / seconds : seconds / SecondsPer(req.unit);
      measured_[it->first] = {req.figure, value, req.unit};
    }
  }
  const std::map<std::string, Figure>& measured() const { return measured_; }

 private:
  static std::string TimeUnitName(benchmark::TimeUnit u) {
    switch (u) {
      case benchmark::kNanosecond:
        return "ns";
      case benchmark::kMicrosecond:
        return "us";
      case benchmark::kMillisecond:
        return "ms";
      default:
        return "s";
    }
  }
  std::map<std::string, Figure> measured_;
};

}  // namespace

void RecordFigure(const std::string& name, double value, const std::string& unit) {
  Figures().push_back({name, value, unit});
}

void TimeFigure(const std::string& benchmark_name, const std::string& figure,
                const std::string& unit) {
  TimeRequests()[benchmark_name] = {figure, unit, 0.0};
}

void RateFigure(const std::string& benchmark_name, const std::string& figure,
                const std::string& unit, double per_iteration) {
  TimeRequests()[benchmark_name] = {figure, unit, per_iteration};
}

int RunBenchmarksAndPrintFigures(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  FigureReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  std::vector<Figure> all = Figures();
  for (const auto& [bench, figure] : reporter.measured()) all.push_back(figure);
  std::printf("\n# figures\n");
  for (const Figure& f : all) std::printf("%s %.6g %s\n", f.name.c_str(), f.value, f.unit.c_str());
  return 0;
}

}  // namespace fleetmap::bench
