// The error-bounded local pass on the Cornell box (paper 004 §4-5, Fig. 7): for each exact method
// and tolerance, seconds, the mean fraction of elements gathered (and projected), the largest
// and RMS relative error against tolerance 0, and how tight the certified bound is; then the
// Monte Carlo baseline's error at several sample counts, and the seconds it needs to reach each
// row's RMS error (log-log interpolation). All cores. Prints Markdown tables. With NAIVE = 1
// (the default), each method's tolerance-0 image is also rendered without occlusion culling
// (every element that can light the point gathered with every element as an occluder): the
// naive exact gather the pass is measured against. SOLUTION is a patch size (a uniform mesh of
// that size, no refinement) or "default" (the default solve, the demo's solution). With
// VERTEX_EXACT = 0 the vertex tracer's tolerance-0 image is not rendered (its rows are judged
// against the hemisphere's; the two agree to 1e-9, local_pass_test.cpp).
// Usage: local_pass_bench [SIZE] [SOLUTION] [NAIVE] [VERTEX_EXACT]   (128 0.07 1 1)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "radiosity/solution_faces.h"
#include "radiosity/solver.h"
#include "reference/monte_carlo.h"
#include "render/irradiance_render.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct Errors {
  double max = 0, rms = 0, tightness_mean = 0, tightness_max = 0;
  int violations = 0;
};

/// Per pixel: |B - B_ref| / B_ref on the brightest channel, over the surface pixels; and
/// error / bound where the bound is positive.
Errors compare(const rad::IrradianceImage& image, const rad::IrradianceImage& reference) {
  Errors e;
  double sum = 0, tight_sum = 0;
  int count = 0, bounded = 0;
  for (size_t i = 0; i < image.surface.size(); ++i) {
    if (!reference.surface[i]) continue;
    const double ref = reference.radiosity.pixels[i].maxCoeff();
    if (!(ref > 0)) continue;
    const double error =
        (image.radiosity.pixels[i] - reference.radiosity.pixels[i]).cwiseAbs().maxCoeff();
    const double relative = error / ref;
    e.max = std::max(e.max, relative);
    sum += relative * relative;
    ++count;
    const double bound = image.bound.pixels[i].maxCoeff();
    if (bound > 0) {
      const double t = error / bound;
      tight_sum += t;
      e.tightness_max = std::max(e.tightness_max, t);
      ++bounded;
    }
    if (((image.radiosity.pixels[i] - reference.radiosity.pixels[i]).cwiseAbs() -
         image.bound.pixels[i])
            .maxCoeff() > 1e-12 * (1 + ref)) {
      ++e.violations;
    }
  }
  e.rms = std::sqrt(sum / std::max(count, 1));
  e.tightness_mean = tight_sum / std::max(bounded, 1);
  return e;
}

double mean_fraction(const std::vector<int>& counts, const std::vector<char>& surface, int total) {
  double sum = 0;
  int n = 0;
  for (size_t i = 0; i < counts.size(); ++i) {
    if (!surface[i]) continue;
    sum += counts[i];
    ++n;
  }
  return sum / std::max(n, 1) / total;
}

}  // namespace

int main(int argc, char** argv) {
  const int size = argc > 1 ? std::stoi(argv[1]) : 128;
  const std::string solution_kind = argc > 2 ? argv[2] : "0.07";
  const bool naive = argc > 3 ? std::stoi(argv[3]) != 0 : true;
  const bool vertex_exact = argc > 4 ? std::stoi(argv[4]) != 0 : true;
  const rad::Scene scene =
      rad::load_scene(std::string(RAD_SOURCE_DIR) + "/data/cornell-box/scene.json");
  rad::SolverSettings settings;
  const bool uniform = solution_kind != "default";
  if (uniform) {
    settings.patch_size = std::stod(solution_kind);
    settings.refine_threshold = 0;  // a uniform mesh: the element count is the patch count x 4
    settings.refine_passes = 0;
  }
  const rad::Solution solution = rad::solve(rad::RayCaster(scene), settings);
  const std::vector<rad::EmittingFace> faces = rad::faces_from_solution(scene, solution);
  rad::CameraSpec spec = *scene.camera;
  spec.width = spec.height = size;
  const rad::Camera camera(spec);
  const rad::RayCaster caster(scene);
  const std::vector<double> tolerances{0.01, 0.05, 0.1, 0.2};

  if (uniform) {
    std::printf(
        "Cornell box, %d elements (patch size %s of the diagonal, no refinement), %dx%d "
        "pixels.\n\n",
        static_cast<int>(faces.size()), solution_kind.c_str(), size, size);
  } else {
    std::printf("Cornell box, %d elements (the default solve), %dx%d pixels.\n\n",
                static_cast<int>(faces.size()), size, size);
  }
  const std::string header =
      "| method | tolerance | seconds | / Monte Carlo 1024 | speed-up | elements gathered (mean) | "
      "clusters (mean) | projected (mean) | max rel. error | RMS rel. error | error / bound "
      "(mean, max) | bound violations | Monte Carlo samples, seconds for the same RMS |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";

  // The hemisphere's exact image is the reference of every row and of the Monte Carlo series.
  struct McPoint {
    int samples;
    double seconds, rms, max;
  };
  std::vector<McPoint> mc;
  // The Monte Carlo samples and seconds for a given RMS error: log-log interpolation between
  // the two sample counts around it.
  const auto mc_for = [&](double rms) -> std::string {
    for (size_t k = 1; k < mc.size(); ++k) {
      if (mc[k].rms <= rms && mc[k - 1].rms > rms) {
        const double t = std::log(rms / mc[k - 1].rms) / std::log(mc[k].rms / mc[k - 1].rms);
        const auto between = [&](double a, double b) {
          return std::exp(std::log(a) + t * std::log(b / a));
        };
        char text[64];
        std::snprintf(text, sizeof text, "%.0f, %.2f", between(mc[k - 1].samples, mc[k].samples),
                      between(mc[k - 1].seconds, mc[k].seconds));
        return text;
      }
    }
    char text[64];
    if (!mc.empty() && rms >= mc.front().rms) {
      std::snprintf(text, sizeof text, "< %d, < %.2f", mc.front().samples, mc.front().seconds);
    } else if (mc.size() >= 2) {
      // Beyond the series: Monte Carlo's RMS falls as samples^-1/2; extrapolate from the last
      // point with that law (its seconds in proportion to the samples).
      const McPoint& last = mc.back();
      const double factor = (last.rms / rms) * (last.rms / rms);
      std::snprintf(text, sizeof text, "~%.0f, ~%.1f (extrapolated)", last.samples * factor,
                    last.seconds * factor);
    } else {
      return "-";
    }
    return text;
  };
  const auto mean = [](const std::vector<int>& counts, const std::vector<char>& surface) {
    double sum = 0;
    int n = 0;
    for (size_t i = 0; i < counts.size(); ++i) {
      if (surface[i]) sum += counts[i], ++n;
    }
    return n > 0 ? sum / n : 0.0;
  };

  const rad::LocalPass hemisphere(scene, faces, rad::Method::hemisphere);
  auto start = Clock::now();
  const rad::IrradianceImage reference =
      rad::render_local_pass(scene, caster, camera, hemisphere, 0);
  const double hemisphere_exact_seconds = seconds_since(start);
  {
    const rad::MonteCarloGatherer gatherer(scene, faces);
    for (const int samples : {16, 64, 256, 1024, 4096}) {
      start = Clock::now();
      const rad::IrradianceImage image =
          rad::render_monte_carlo(scene, caster, camera, gatherer, samples);
      const double s = seconds_since(start);
      const Errors e = compare(image, reference);
      mc.push_back({samples, s, e.rms, e.max});
    }
  }
  double mc_1024 = 0;
  for (const McPoint& p : mc) {
    if (p.samples == 1024) mc_1024 = p.seconds;
  }

  std::printf("%s", header.c_str());
  const auto row = [&](const std::string& label, const std::string& tolerance, double seconds,
                       double exact_seconds, const rad::IrradianceImage& image, int face_count,
                       bool exact) {
    const Errors e = compare(image, reference);
    char tightness[64] = "-";
    if (!exact)
      std::snprintf(tightness, sizeof tightness, "%.3f, %.3f", e.tightness_mean, e.tightness_max);
    std::printf(
        "| %s | %s | %.1f | %.2f | %s | %.1f%% | %.0f | %.1f%% | %.2e | %.2e | %s | %s | %s |\n",
        label.c_str(), tolerance.c_str(), seconds, seconds / mc_1024,
        exact_seconds > 0 ? std::to_string(exact_seconds / seconds).substr(0, 4).c_str() : "-",
        100 * mean_fraction(image.gathered_exactly, image.surface, face_count),
        mean(image.clusters, image.surface),
        100 * mean_fraction(image.projected, image.surface, face_count), e.max, e.rms, tightness,
        exact ? "-" : std::to_string(e.violations).c_str(), exact ? "-" : mc_for(e.rms).c_str());
    std::fflush(stdout);
  };
  for (const rad::Method method : {rad::Method::hemisphere, rad::Method::vertex}) {
    const std::string name = rad::method_name(method);
    const rad::LocalPass pass(scene, faces, method);
    double exact_seconds = 0;
    if (method == rad::Method::hemisphere) {
      exact_seconds = hemisphere_exact_seconds;
      row(name, "0", exact_seconds, exact_seconds, reference, pass.face_count(), true);
    } else if (vertex_exact) {
      start = Clock::now();
      const rad::IrradianceImage image = rad::render_local_pass(scene, caster, camera, pass, 0);
      exact_seconds = seconds_since(start);
      row(name, "0", exact_seconds, exact_seconds, image, pass.face_count(), true);
    } else {
      std::printf("| %s | 0 | not run | | | | | | | | | | |\n", name.c_str());
    }
    if (naive) {
      rad::LocalPassSettings no_culling;
      no_culling.occlusion_culling = false;
      const rad::LocalPass naive_pass(scene, faces, method, no_culling);
      start = Clock::now();
      const rad::IrradianceImage image =
          rad::render_local_pass(scene, caster, camera, naive_pass, 0);
      row(name + ", no culling", "0", seconds_since(start), exact_seconds, image, pass.face_count(),
          true);
    }
    for (const double tolerance : tolerances) {
      start = Clock::now();
      const rad::IrradianceImage image =
          rad::render_local_pass(scene, caster, camera, pass, tolerance);
      char text[16];
      std::snprintf(text, sizeof text, "%.2f", tolerance);
      row(name, text, seconds_since(start), exact_seconds, image, pass.face_count(), false);
    }
  }
  std::printf(
      "\n| Monte Carlo samples per pixel | seconds | RMS rel. error vs exact | max rel. error vs "
      "exact |\n|---|---|---|---|\n");
  for (const McPoint& p : mc)
    std::printf("| %d | %.2f | %.2e | %.2e |\n", p.samples, p.seconds, p.rms, p.max);
  return 0;
}
