#include "viz/sweep.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>

#include "localpass/local_pass.h"
#include "localpass/monte_carlo.h"
#include "scene/error.h"
#include "scene/ray_caster.h"
#include "viz/atomic_file.h"
#include "viz/charts.h"
#include "viz/image_io.h"
#include "viz/offscreen_display.h"

namespace rad {
namespace {

using Clock = std::chrono::steady_clock;

/// A reference read from a file holds floats: 2^-24 relative rounding per channel, doubled.
constexpr double kFloatSlack = 0x1p-23;

std::string number(double v) {
  std::ostringstream out;
  out << std::setprecision(10) << v;
  return out.str();
}

ExactMethod exact_method(const std::string& name) {
  if (name == "hemisphere") return ExactMethod::hemisphere;
  if (name == "vertex") return ExactMethod::vertex;
  throw Error("unknown exact method \"" + name + "\" (hemisphere or vertex)");
}

}  // namespace

std::string SweepRow::label() const {
  return exact() ? method + " T=" + number(tolerance) : method + " N=" + std::to_string(samples);
}

std::string SweepRow::slug() const {
  return exact() ? method + "_T" + number(tolerance) : method + "_N" + std::to_string(samples);
}

// The default slack, 1e-8: the exact methods agree to ~1e-9 relative (README, "The local
// pass"), so a smaller excess over the bound is rounding, not a violation.
void compare_to_reference(const LocalPassImage& image, const LocalPassImage& reference, SweepRow& row, ErrorMap* map,
                          double slack_fraction) {
  ErrorMap errors = relative_error_map(image.radiosity, reference.radiosity);
  row.error = errors.stats;
  row.violations = row.exact() ? 0 : -1;
  row.error_over_bound_max = 0;
  if (row.exact()) {
    for (size_t i = 0; i < image.radiosity.pixels.size(); ++i) {
      const Rgb difference = (image.radiosity.pixels[i] - reference.radiosity.pixels[i]).cwiseAbs();
      const Rgb& bound = image.bound.pixels[i];
      const double slack = slack_fraction * reference.radiosity.pixels[i].cwiseAbs().maxCoeff();
      if (!((difference - bound).maxCoeff() <= slack)) ++row.violations;  // NaN counts
      for (int c = 0; c < 3; ++c) {
        if (bound[c] > 0) row.error_over_bound_max = std::max(row.error_over_bound_max, difference[c] / bound[c]);
      }
    }
  }
  if (map) *map = std::move(errors);
}

std::vector<SweepRow> run_sweep(const Scene& scene, const std::vector<EmittingFace>& faces, const Camera& camera,
                                const SweepSettings& settings, const std::filesystem::path& folder,
                                const SweepProgress& progress, const SweepRowDone& row_done) {
  for (const std::string& m : settings.methods) {
    if (m != "hemisphere" && m != "vertex" && m != "montecarlo") {
      throw Error("unknown method \"" + m + "\" (hemisphere, vertex or montecarlo)");
    }
  }
  ensure_display();  // the charts and heat maps need one: fail now, not after the renders
  const RayCaster caster(scene);
  const double pixels = static_cast<double>(camera.spec().width) * camera.spec().height;
  const auto reporter = [&](const std::string& what) {
    return [&progress, what, pixels](size_t done) {
      if (progress) progress(what, done / pixels);
    };
  };

  // Set up one pass per exact method (faces, octree, culling), outside the timed renders.
  std::optional<LocalPass> passes[2];
  const auto pass_for = [&](const std::string& method) -> const LocalPass& {
    const ExactMethod m = exact_method(method);
    std::optional<LocalPass>& pass = passes[m == ExactMethod::vertex ? 1 : 0];
    if (!pass) pass.emplace(scene, faces, m);
    return *pass;
  };
  const auto time_exact = [&](const std::string& method, double tolerance, LocalPassImage& out) {
    const LocalPass& pass = pass_for(method);
    const auto start = Clock::now();
    out = render_local_pass(scene, caster, camera, pass, tolerance, reporter(method + " T=" + number(tolerance)));
    return std::chrono::duration<double>(Clock::now() - start).count();
  };

  LocalPassImage reference;
  double reference_seconds = 0, slack = 1e-8;
  const bool reference_from_file = !settings.reference_file.empty();
  if (reference_from_file) {
    reference.radiosity = read_exr(settings.reference_file);
    if (reference.radiosity.width != camera.width() || reference.radiosity.height != camera.height()) {
      throw InputError(settings.reference_file.string() + ": " + std::to_string(reference.radiosity.width) + "x" +
                       std::to_string(reference.radiosity.height) + " pixels, but the sweep renders " +
                       std::to_string(camera.width()) + "x" + std::to_string(camera.height()));
    }
    slack = kFloatSlack;
  } else {
    reference_seconds = time_exact(settings.reference_method, 0, reference);
  }
  write_exr(folder / "reference.exr", reference.radiosity);
  write_png_preview(folder / "reference.png", reference.radiosity);

  std::vector<SweepRow> rows;
  std::vector<ErrorMap> maps;
  const auto record = [&](SweepRow row, const LocalPassImage& image, double seconds) {
    row.seconds = seconds;
    if (row.exact()) {
      const LocalPassSummary summary = summarize(image);
      row.projected_mean = summary.projected_mean;
      row.projected_max = summary.projected_max;
    }
    ErrorMap map;
    compare_to_reference(image, reference, row, &map, slack);
    row.image = "images/" + row.slug() + ".exr";
    write_exr(folder / row.image, image.radiosity);
    write_png_preview(std::filesystem::path(folder / row.image).replace_extension(".png"), image.radiosity);
    rows.push_back(std::move(row));
    maps.push_back(std::move(map));
    if (row_done) row_done(rows.back());
  };

  for (const std::string& method : settings.methods) {
    if (method == "montecarlo") {
      const MonteCarloGatherer gatherer(scene, faces);
      for (int n : settings.samples) {
        SweepRow row;
        row.method = method;
        row.samples = n;
        const auto start = Clock::now();
        LocalPassImage image = render_monte_carlo(scene, caster, camera, gatherer, n, reporter(row.label()));
        record(std::move(row), image, std::chrono::duration<double>(Clock::now() - start).count());
      }
      continue;
    }
    for (double t : settings.tolerances) {
      SweepRow row;
      row.method = method;
      row.tolerance = t;
      if (t == 0 && method == settings.reference_method && !reference_from_file) {
        record(std::move(row), reference, reference_seconds);
        continue;
      }
      LocalPassImage image;
      const double seconds = time_exact(method, t, image);
      record(std::move(row), image, seconds);
    }
  }

  // Error maps on one colour scale: the largest error of the exact rows (Monte Carlo's few
  // samples can be off by 10x and more, which would leave the exact maps one flat colour);
  // Monte Carlo maps clamp there. With no exact row, the largest error of all.
  double top = 0, top_all = 0;
  for (const SweepRow& row : rows) {
    if (!std::isfinite(row.error.max)) continue;
    top_all = std::max(top_all, row.error.max);
    if (row.exact()) top = std::max(top, row.error.max);
  }
  if (!(top > 0)) top = top_all;
  for (size_t i = 0; i < rows.size(); ++i) {
    const std::filesystem::path exr = folder / "error_maps" / (rows[i].slug() + ".exr");
    write_error_map(exr, std::filesystem::path(exr).replace_extension(".png"), maps[i],
                    "relative error of " + rows[i].label() + " (max " + number(rows[i].error.max) + ")", top);
  }
  write_sweep_csv(folder / "results.csv", rows);
  write_sweep_charts(folder, rows);
  return rows;
}

void write_sweep_csv(const std::filesystem::path& file, const std::vector<SweepRow>& rows) {
  write_text_file(file, [&](std::ostream& out) {
    out << "method,tolerance,samples,seconds,projected_mean,projected_max,error_max,error_mean,error_rms,"
           "bound_violations,error_over_bound_max,pixels,image\n";
    for (const SweepRow& r : rows) {
      out << r.method << ',' << (r.exact() ? number(r.tolerance) : "") << ','
          << (r.exact() ? "" : std::to_string(r.samples)) << ',' << number(r.seconds) << ','
          << (r.exact() ? number(r.projected_mean) : "") << ',' << (r.exact() ? number(r.projected_max) : "") << ','
          << number(r.error.max) << ',' << number(r.error.mean) << ',' << number(r.error.rms) << ','
          << (r.exact() ? std::to_string(r.violations) : "") << ','
          << (r.exact() ? number(r.error_over_bound_max) : "") << ',' << r.error.pixels << ',' << r.image << '\n';
    }
  });
}

void write_sweep_charts(const std::filesystem::path& folder, const std::vector<SweepRow>& rows) {
  // One series per method, in the rows' order; `x` and `y` pick the coordinates.
  // Tolerance-0 rows are left out: they are the reference, or agree with it to rounding
  // (~1e-11), which says nothing about the tolerance and would squash the log scale.
  const auto series_by_method = [&](bool exact_only, const std::string& suffix, auto x, auto y) {
    std::vector<ChartSeries> out;
    for (const SweepRow& r : rows) {
      if ((exact_only && !r.exact()) || (r.exact() && r.tolerance == 0)) continue;
      const std::string name = r.method + suffix;
      auto it = std::find_if(out.begin(), out.end(), [&](const ChartSeries& s) { return s.name == name; });
      if (it == out.end()) it = out.insert(out.end(), ChartSeries{name, {}, {}});
      it->x.push_back(x(r));
      it->y.push_back(y(r));
    }
    return out;
  };
  const auto tolerance = [](const SweepRow& r) { return r.tolerance; };

  // All three charts have log axes.
  const auto log_log = [](std::string title, std::string x_label, std::string y_label, LineChart::Corner legend) {
    LineChart chart;
    chart.title = std::move(title);
    chart.x_label = std::move(x_label);
    chart.y_label = std::move(y_label);
    chart.log_x = chart.log_y = true;
    chart.legend = legend;
    return chart;
  };

  LineChart error_chart = log_log("Relative error against tolerance (reference: tolerance 0)", "tolerance T",
                                  "relative error", LineChart::Corner::bottom_right);
  error_chart.series = series_by_method(true, " max", tolerance, [](const SweepRow& r) { return r.error.max; });
  for (ChartSeries& s : series_by_method(true, " RMS", tolerance, [](const SweepRow& r) { return r.error.rms; })) {
    error_chart.series.push_back(std::move(s));
  }
  // What the bound promises against the exact value: |e| <= T / (1 - T) (README).
  ChartSeries promise{"T / (1 - T)", {}, {}};
  for (const SweepRow& r : rows) {
    if (r.exact() && r.tolerance > 0 && std::find(promise.x.begin(), promise.x.end(), r.tolerance) == promise.x.end()) {
      promise.x.push_back(r.tolerance);
    }
  }
  std::sort(promise.x.begin(), promise.x.end());
  for (double t : promise.x) promise.y.push_back(t / (1 - t));
  error_chart.series.push_back(std::move(promise));
  write_chart_png(folder / "error_vs_tolerance.png", error_chart);

  LineChart time_chart =
      log_log("Render time against tolerance", "tolerance T", "seconds", LineChart::Corner::top_right);
  time_chart.series = series_by_method(true, "", tolerance, [](const SweepRow& r) { return r.seconds; });
  write_chart_png(folder / "time_vs_tolerance.png", time_chart);

  LineChart tradeoff = log_log("RMS error against render time (all methods)", "seconds", "RMS relative error",
                               LineChart::Corner::bottom_left);
  tradeoff.series = series_by_method(false, "", [](const SweepRow& r) { return r.seconds; },
                                     [](const SweepRow& r) { return r.error.rms; });
  write_chart_png(folder / "error_vs_time.png", tradeoff);
}

}  // namespace rad
