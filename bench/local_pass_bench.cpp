// The error-bounded local pass on the Cornell box (paper 004 §4-5, Fig. 7): for each exact method
// and tolerance, seconds, the mean fraction of elements gathered (and projected), the largest
// and RMS relative error against tolerance 0, and how tight the certified bound is; then the
// Monte Carlo baseline's error at several sample counts, and the seconds it needs to reach each
// row's RMS error (log-log interpolation). All cores. Prints Markdown tables. With NAIVE = 1
// (the default), each method's tolerance-0 image is also rendered without occlusion culling
// (every element that can light the point gathered with every element as an occluder): the
// naive exact gather the pass is measured against.
// Usage: local_pass_bench [SIZE] [PATCH_SIZE] [NAIVE]   (SIZE x SIZE, default 128; patch 0.07; 1)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "localpass/monte_carlo.h"
#include "radiosity/solution_faces.h"
#include "radiosity/solver.h"
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
  const double patch_size = argc > 2 ? std::stod(argv[2]) : 0.07;
  const bool naive = argc > 3 ? std::stoi(argv[3]) != 0 : true;
  const rad::Scene scene =
      rad::load_scene(std::string(RAD_SOURCE_DIR) + "/data/cornell-box/scene.json");
  rad::SolverSettings settings;
  settings.patch_size = patch_size;
  settings.refine_threshold = 0;  // a uniform mesh: the element count is the patch count x 4
  settings.refine_passes = 0;
  const rad::Solution solution = rad::solve(rad::RayCaster(scene), settings);
  const std::vector<rad::EmittingFace> faces = rad::faces_from_solution(scene, solution);
  rad::CameraSpec spec = *scene.camera;
  spec.width = spec.height = size;
  const rad::Camera camera(spec);
  const rad::RayCaster caster(scene);
  const std::vector<double> tolerances{0.01, 0.05, 0.1, 0.2, 0.5};

  std::printf(
      "Cornell box, %d elements (patch size %.2f of the diagonal, no refinement), %dx%d "
      "pixels.\n\n",
      static_cast<int>(faces.size()), patch_size, size, size);
  std::printf(
      "| method | tolerance | seconds | speed-up | elements gathered (mean) | projected (mean) | "
      "max rel. error "
      "| RMS rel. error | error / bound (mean, max) | bound violations | Monte Carlo seconds for "
      "the same RMS |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");

  // Monte Carlo series against the exact hemisphere image (filled in after the reference).
  struct McPoint {
    int samples;
    double seconds, rms, max;
  };
  std::vector<McPoint> mc;
  const auto mc_seconds_for = [&](double rms) -> std::string {
    for (size_t k = 1; k < mc.size(); ++k) {
      if (mc[k].rms <= rms && mc[k - 1].rms > rms) {
        // Interpolate log(seconds) against log(rms) between the two sample counts.
        const double t = std::log(rms / mc[k - 1].rms) / std::log(mc[k].rms / mc[k - 1].rms);
        char text[32];
        std::snprintf(text, sizeof text, "%.2f",
                      std::exp(std::log(mc[k - 1].seconds) +
                               t * std::log(mc[k].seconds / mc[k - 1].seconds)));
        return text;
      }
    }
    if (!mc.empty() && rms >= mc.front().rms)
      return "< " + std::to_string(mc.front().seconds).substr(0, 5);
    return mc.empty() ? "-" : "> " + std::to_string(mc.back().seconds).substr(0, 6);
  };

  std::vector<std::string> rows;
  rad::IrradianceImage hemisphere_reference;
  for (const rad::Method method : {rad::Method::hemisphere, rad::Method::vertex}) {
    const std::string name = rad::method_name(method);
    const rad::LocalPass pass(scene, faces, method);
    auto start = Clock::now();
    const rad::IrradianceImage reference = rad::render_local_pass(scene, caster, camera, pass, 0);
    const double reference_seconds = seconds_since(start);
    if (method == rad::Method::hemisphere) {
      hemisphere_reference = reference;
      const rad::MonteCarloGatherer gatherer(scene, faces);
      for (const int samples : {16, 64, 256, 1024, 4096, 16384}) {
        start = Clock::now();
        const rad::IrradianceImage image =
            rad::render_monte_carlo(scene, caster, camera, gatherer, samples);
        const double s = seconds_since(start);
        const Errors e = compare(image, reference);
        mc.push_back({samples, s, e.rms, e.max});
        if (s > 4 * reference_seconds) break;  // slower than the exact image already
      }
    } else {
      const Errors e = compare(reference, hemisphere_reference);
      std::fprintf(stderr, "vertex vs hemisphere at tolerance 0: max relative difference %.2e\n",
                   e.max);
    }
    std::printf(
        "| %s | 0 | %.1f | 1.00 | %.1f%% | %.1f%% | 0 | 0 | - | 0 | - |\n", name.c_str(),
        reference_seconds,
        100 * mean_fraction(reference.gathered_exactly, reference.surface, pass.face_count()),
        100 * mean_fraction(reference.projected, reference.surface, pass.face_count()));
    if (naive) {
      rad::LocalPassSettings no_culling;
      no_culling.occlusion_culling = false;
      const rad::LocalPass naive_pass(scene, faces, method, no_culling);
      start = Clock::now();
      const rad::IrradianceImage image =
          rad::render_local_pass(scene, caster, camera, naive_pass, 0);
      const double s = seconds_since(start);
      const Errors e = compare(image, reference);
      std::printf(
          "| %s, no culling | 0 | %.1f | %.2f | %.1f%% | %.1f%% | %.2e | %.2e | - | %d | - |\n",
          name.c_str(), s, reference_seconds / s,
          100 * mean_fraction(image.gathered_exactly, image.surface, pass.face_count()),
          100 * mean_fraction(image.projected, image.surface, pass.face_count()), e.max, e.rms,
          e.violations);
    }
    for (const double tolerance : tolerances) {
      start = Clock::now();
      const rad::IrradianceImage image =
          rad::render_local_pass(scene, caster, camera, pass, tolerance);
      const double s = seconds_since(start);
      const Errors e = compare(image, reference);
      std::printf(
          "| %s | %.2f | %.1f | %.2f | %.1f%% | %.1f%% | %.2e | %.2e | %.3f, %.3f | %d | %s |\n",
          name.c_str(), tolerance, s, reference_seconds / s,
          100 * mean_fraction(image.gathered_exactly, image.surface, pass.face_count()),
          100 * mean_fraction(image.projected, image.surface, pass.face_count()), e.max, e.rms,
          e.tightness_mean, e.tightness_max, e.violations, mc_seconds_for(e.rms).c_str());
      std::fflush(stdout);
    }
  }
  std::printf(
      "\n| Monte Carlo samples per pixel | seconds | RMS rel. error vs exact | max rel. error vs "
      "exact |\n|---|---|---|---|\n");
  for (const McPoint& p : mc)
    std::printf("| %d | %.2f | %.2e | %.2e |\n", p.samples, p.seconds, p.rms, p.max);
  return 0;
}
