// Turns Google Benchmark results into the project's figures: one `name value unit` line per
// figure, printed after the benchmark table, which ./run_bench.sh collects from every
// program. Timings come from named benchmarks; sizes and counts are recorded directly.
#pragma once

#include <string>

namespace fleetmap::bench {

// A figure that is not a timing (bytes, counts, ratios).
void RecordFigure(const std::string& name, double value, const std::string& unit);

// The figure `figure` is the real time per iteration of benchmark `benchmark_name`,
// converted to `unit` ("ns", "us", "ms" or "s").
void TimeFigure(const std::string& benchmark_name, const std::string& figure,
                const std::string& unit);

// The figure `figure` is `per_iteration / seconds per iteration` of benchmark
// `benchmark_name`: a rate, e.g. simulated seconds per wall-clock second.
void RateFigure(const std::string& benchmark_name, const std::string& figure,
                const std::string& unit, double per_iteration);

// Runs the registered benchmarks (honouring --benchmark_* flags), then prints the figures.
int RunBenchmarksAndPrintFigures(int argc, char** argv);

}  // namespace fleetmap::bench
