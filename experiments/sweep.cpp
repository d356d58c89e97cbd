#include "experiments/sweep.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>

#include "formats/atomic_file.h"
#include "formats/image_io.h"
#include "localpass/local_pass.h"
#include "reference/monte_carlo.h"
#include "scene/error.h"
#include "scene/ray_caster.h"

namespace rad {
namespace {

using Clock = std::chrono::steady_clock;

/// A reference read from a file holds floats: 2^-24 relative rounding per channel, doubled.
constexpr double kFloatSlack = 0x1p-23;

}  // namespace

std::string csv_number(double v) {
  std::ostringstream out;
  out << std::setprecision(10) << v;
  return out.str();
}

std::string SweepRow::label() const {
  const std::string name = method_name(method);
  return exact() ? name + " T=" + csv_number(tolerance) : name + " N=" + std::to_string(samples);
}

std::string SweepRow::slug() const {
  const std::string name = method_name(method);
  return exact() ? name + "_T" + csv_number(tolerance) : name + "_N" + std::to_string(samples);
}

// The default slack, 1e-8: the exact methods agree to ~1e-9 relative (docs/algorithms.md, "The
// local pass"), so a smaller excess over the bound is rounding, not a violation.
void compare_to_reference(const IrradianceImage& image, const IrradianceImage& reference,
                          SweepRow& row, ErrorMap* map, double slack_fraction) {
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
        if (bound[c] > 0)
          row.error_over_bound_max = std::max(row.error_over_bound_max, difference[c] / bound[c]);
      }
    }
  }
  if (map) *map = std::move(errors);
}

SweepResult run_sweep(const Scene& scene, const std::vector<EmittingFace>& faces,
                      const Camera& camera, const SweepSettings& settings,
                      const std::filesystem::path& folder, const SweepProgress& progress,
                      const SweepRowDone& row_done, const Job& job) {
  if (!is_exact(settings.reference_method))
    throw Error("the sweep's reference method must be exact");
  const RayCaster caster(scene);
  const double pixels = static_cast<double>(camera.spec().width) * camera.spec().height;
  const auto reporter = [&](const std::string& what) {
    return [&progress, what, pixels](size_t done) {
      if (progress) progress(what, done / pixels);
    };
  };

  // Set up one pass per exact method (faces, octree, culling), outside the timed renders.
  std::optional<LocalPass> passes[2];
  const auto pass_for = [&](Method method) -> const LocalPass& {
    std::optional<LocalPass>& pass = passes[method == Method::vertex ? 1 : 0];
    if (!pass) pass.emplace(scene, faces, method);
    return *pass;
  };
  const auto time_exact = [&](Method method, double tolerance, IrradianceImage& out) {
    const LocalPass& pass = pass_for(method);
    const auto start = Clock::now();
    out = render_local_pass(scene, caster, camera, pass, tolerance,
                            reporter(method_name(method) + " T=" + csv_number(tolerance)), job);
    return std::chrono::duration<double>(Clock::now() - start).count();
  };

  IrradianceImage reference;
  double reference_seconds = 0, slack = 1e-8;
  const bool reference_from_file = !settings.reference_file.empty();
  if (reference_from_file) {
    job.step([&] {
      if (!job.is_root()) return;
      reference.radiosity = read_exr(settings.reference_file);
      if (reference.radiosity.width != camera.width() ||
          reference.radiosity.height != camera.height()) {
        throw InputError(
            settings.reference_file.string() + ": " + std::to_string(reference.radiosity.width) +
            "x" + std::to_string(reference.radiosity.height) + " pixels, but the sweep renders " +
            std::to_string(camera.width()) + "x" + std::to_string(camera.height()));
      }
    });
    slack = kFloatSlack;
  } else {
    reference_seconds = time_exact(settings.reference_method, 0, reference);
  }
  // Every preview at the reference's exposure, so that they compare side by side.
  const double exposure = auto_exposure(reference.radiosity);
  // The root writes between renders: as a step, so that a write that fails ends every process
  // rather than leaving the others waiting in the next render (distributed/job.h).
  job.step([&] {
    if (!job.is_root()) return;
    write_exr(folder / "reference.exr", reference.radiosity);
    write_png_preview(folder / "reference.png", reference.radiosity, exposure);
  });

  std::vector<SweepRow> rows;
  std::vector<ErrorMap> maps;
  const auto record_on_root = [&](SweepRow row, const IrradianceImage& image, double seconds) {
    row.seconds = seconds;
    if (row.exact()) {
      const IrradianceSummary summary = summarize(image);
      row.projected_mean = summary.projected_mean;
      row.projected_max = summary.projected_max;
    }
    ErrorMap map;
    compare_to_reference(image, reference, row, &map, slack);
    row.image = "images/" + row.slug() + ".exr";
    write_exr(folder / row.image, image.radiosity);
    write_png_preview(std::filesystem::path(folder / row.image).replace_extension(".png"),
                      image.radiosity, exposure);
    rows.push_back(std::move(row));
    maps.push_back(std::move(map));
    if (row_done) row_done(rows.back());
  };
  const auto record = [&](SweepRow row, const IrradianceImage& image, double seconds) {
    job.step([&] {
      if (job.is_root()) record_on_root(std::move(row), image, seconds);
    });  // the others' images hold only the tiles they rendered
  };

  for (const Method method : settings.methods) {
    if (!is_exact(method)) {
      const MonteCarloGatherer gatherer(scene, faces);
      for (int n : settings.samples) {
        SweepRow row;
        row.method = method;
        row.samples = n;
        const auto start = Clock::now();
        IrradianceImage image =
            render_monte_carlo(scene, caster, camera, gatherer, n, reporter(row.label()), job);
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
      IrradianceImage image;
      const double seconds = time_exact(method, t, image);
      record(std::move(row), image, seconds);
    }
  }

  if (!job.is_root()) return {};
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
    write_error_map_exr(folder / "error_maps" / (rows[i].slug() + ".exr"), maps[i]);
  }
  write_sweep_csv(folder / "results.csv", rows);
  return {std::move(rows), std::move(maps), top};
}

void write_sweep_csv(const std::filesystem::path& file, const std::vector<SweepRow>& rows) {
  write_text_file(file, [&](std::ostream& out) {
    out << "method,tolerance,samples,seconds,projected_mean,projected_max,error_max,error_mean,"
           "error_rms,"
           "bound_violations,error_over_bound_max,pixels,image\n";
    for (const SweepRow& r : rows) {
      out << method_name(r.method) << ',' << (r.exact() ? csv_number(r.tolerance) : "") << ','
          << (r.exact() ? "" : std::to_string(r.samples)) << ',' << csv_number(r.seconds) << ','
          << (r.exact() ? csv_number(r.projected_mean) : "") << ','
          << (r.exact() ? csv_number(r.projected_max) : "") << ',' << csv_number(r.error.max) << ','
          << csv_number(r.error.mean) << ',' << csv_number(r.error.rms) << ','
          << (r.exact() ? std::to_string(r.violations) : "") << ','
          << (r.exact() ? csv_number(r.error_over_bound_max) : "") << ',' << r.error.pixels << ','
          << r.image << '\n';
    }
  });
}

}  // namespace rad
