#include "viz/sweep_figures.h"

#include <algorithm>

#include "viz/charts.h"
#include "viz/error_heat_map.h"

namespace rad {

void write_sweep_figures(const std::filesystem::path& folder, const SweepResult& sweep) {
  for (size_t i = 0; i < sweep.rows.size(); ++i) {
    const SweepRow& row = sweep.rows[i];
    write_error_heat_map(
        folder / "error_maps" / (row.slug() + ".png"), sweep.maps[i],
        "relative error of " + row.label() + " (max " + csv_number(row.error.max) + ")",
        sweep.error_scale);
  }
  write_sweep_charts(folder, sweep.rows);
}

void write_sweep_charts(const std::filesystem::path& folder, const std::vector<SweepRow>& rows) {
  // One series per method, in the rows' order; `x` and `y` pick the coordinates.
  // Tolerance-0 rows are left out: they are the reference, or agree with it to rounding
  // (~1e-11), which says nothing about the tolerance and would squash the log scale.
  const auto series_by_method = [&](bool exact_only, const std::string& suffix, auto x, auto y) {
    std::vector<ChartSeries> out;
    for (const SweepRow& r : rows) {
      if ((exact_only && !r.exact()) || (r.exact() && r.tolerance == 0)) continue;
      const std::string name = method_name(r.method) + suffix;
      auto it = std::find_if(out.begin(), out.end(),
                             [&](const ChartSeries& s) { return s.name == name; });
      if (it == out.end()) it = out.insert(out.end(), ChartSeries{name, {}, {}});
      it->x.push_back(x(r));
      it->y.push_back(y(r));
    }
    return out;
  };
  const auto tolerance = [](const SweepRow& r) { return r.tolerance; };

  // All three charts have log axes.
  const auto log_log = [](std::string title, std::string x_label, std::string y_label,
                          LineChart::Corner legend) {
    LineChart chart;
    chart.title = std::move(title);
    chart.x_label = std::move(x_label);
    chart.y_label = std::move(y_label);
    chart.log_x = chart.log_y = true;
    chart.legend = legend;
    return chart;
  };

  LineChart error_chart = log_log("Relative error against tolerance (reference: tolerance 0)",
                                  "tolerance T", "relative error", LineChart::Corner::bottom_right);
  error_chart.series =
      series_by_method(true, " max", tolerance, [](const SweepRow& r) { return r.error.max; });
  for (ChartSeries& s :
       series_by_method(true, " RMS", tolerance, [](const SweepRow& r) { return r.error.rms; })) {
    error_chart.series.push_back(std::move(s));
  }
  // What the bound promises against the exact value: |e| <= T / (1 - T) (localpass/local_pass.h).
  ChartSeries promise{"T / (1 - T)", {}, {}};
  for (const SweepRow& r : rows) {
    if (r.exact() && r.tolerance > 0 &&
        std::find(promise.x.begin(), promise.x.end(), r.tolerance) == promise.x.end()) {
      promise.x.push_back(r.tolerance);
    }
  }
  std::sort(promise.x.begin(), promise.x.end());
  for (double t : promise.x) promise.y.push_back(t / (1 - t));
  error_chart.series.push_back(std::move(promise));
  write_chart_png(folder / "error_vs_tolerance.png", error_chart);

  LineChart time_chart = log_log("Render time against tolerance", "tolerance T", "seconds",
                                 LineChart::Corner::top_right);
  time_chart.series =
      series_by_method(true, "", tolerance, [](const SweepRow& r) { return r.seconds; });
  write_chart_png(folder / "time_vs_tolerance.png", time_chart);

  LineChart tradeoff = log_log("RMS error against render time (all methods)", "seconds",
                               "RMS relative error", LineChart::Corner::bottom_left);
  tradeoff.series = series_by_method(
      false, "", [](const SweepRow& r) { return r.seconds; },
      [](const SweepRow& r) { return r.error.rms; });
  write_chart_png(folder / "error_vs_time.png", tradeoff);
}

}  // namespace rad
