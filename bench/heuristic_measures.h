#pragma once
/// The measures the benchmarks of the heuristics (refraction_bench, glossy_bench) share: their
/// error against a path-traced reference, the reference's own, and a median time.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "formats/points_csv.h"
#include "reference/path_tracer.h"

namespace rad::bench {

/// RMS over points and channels of (value - reference) / the reference's mean over the points,
/// in %.
inline double rms_error(const std::vector<Rgb>& value, const std::vector<Rgb>& reference) {
  Rgb mean = Rgb::Zero();
  for (const Rgb& r : reference) mean += r;
  mean /= static_cast<double>(reference.size());
  double sum = 0;
  for (size_t i = 0; i < value.size(); ++i)
    sum += (value[i] - reference[i]).cwiseQuotient(mean).squaredNorm();
  return 100 * std::sqrt(sum / (3.0 * static_cast<double>(value.size())));
}

/// A path-traced reference at the points (seeded by the point's index), and its own error in
/// the measure of rms_error: that of the values moved by one standard error.
struct Reference {
  std::vector<Rgb> value, standard_error;
  double noise = 0;
};
inline Reference trace_reference(const PathTracer& tracer, const std::vector<ProbePoint>& points,
                                 int paths) {
  Reference r{std::vector<Rgb>(points.size()), std::vector<Rgb>(points.size()), 0};
  tbb::parallel_for(size_t(0), points.size(), [&](size_t i) {
    const PathTraceEstimate e = tracer.irradiance(points[i].x, points[i].n, paths, i);
    r.value[i] = e.mean;
    r.standard_error[i] = e.standard_error;
  });
  std::vector<Rgb> shifted(points.size());
  for (size_t i = 0; i < points.size(); ++i) shifted[i] = r.value[i] + r.standard_error[i];
  r.noise = rms_error(shifted, r.value);
  return r;
}

/// The median over repeated runs of `run` in seconds: at least 3 runs, more while the total
/// stays under a second (a shared machine's noise swamps a single run of milliseconds); a run
/// of 10 s or more is timed once (the benchmarks would otherwise take an hour).
template <class Run>
double median_seconds(const Run& run) {
  std::vector<double> times;
  double total = 0;
  while (times.size() < 3 || total < 1.0) {
    const auto start = std::chrono::steady_clock::now();
    run();
    times.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    total += times.back();
    if (times.back() >= 10.0) break;
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

}  // namespace rad::bench
