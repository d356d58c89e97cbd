// `radiosity probe SCENE --points P.csv [--solution S.vtp [--tolerance T]] [--method
// hemisphere|vertex|montecarlo|pathtrace] [-o OUT.csv]`: exact irradiance at given points: direct
// lighting only (polygons radiate their emission, all occlude; mirrors reflect it), or from a
// solution through the error-bounded local pass; or, as the reference, the scene path-traced.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/common.h"
#include "cli/inputs.h"
#include "distributed/job.h"
#include "distributed/packed_bytes.h"
#include "formats/atomic_file.h"
#include "formats/points_csv.h"
#include "formats/solution_io.h"
#include "localpass/local_pass.h"
#include "localpass/method.h"
#include "radiosity/solution_faces.h"
#include "reference/monte_carlo.h"
#include "reference/path_tracer.h"
#include "scene/error.h"
#include "scene/polygon_faces.h"

namespace rad::cli {
namespace {

/// The local pass's methods and the path tracer.
std::vector<std::string> probe_method_names() {
  std::vector<std::string> names = method_names();
  names.push_back("pathtrace");
  return names;
}

struct ProbeOptions {
  std::string scene;
  std::string points;
  std::string method = "hemisphere";
  std::string solution;  ///< empty: direct lighting only
  double tolerance = 0;
  int samples = 64;
  double target_error = 0;  ///< pathtrace: batches until this relative standard error
  std::string output;       ///< empty: stdout
  int threads = 0;
  LocalPassSettings settings;             ///< The refraction knob
  bool no_interface_reflections = false;  ///< pathtrace: the heuristic's model of interfaces
};

/// The batches of a reference: at most this many of --samples paths each.
constexpr int max_batches = 4096;

/// H at a point from batches of `paths` paths, batch b seeded by (point, b), until every
/// channel's standard error is at most `target` of its mean (0: one batch) or max_batches. The
/// batches are independent and of equal size, so the mean of their means is the mean of all the
/// paths and its standard error is sqrt(sum se_b^2) / batches. The first batch is the plain
/// run's, and the stopping rule looks only at this point's batches: the result does not depend
/// on threads.
PathTraceEstimate traced_to_target(const PathTracer& tracer, const ProbePoint& p, int paths,
                                   double target, size_t point) {
  Rgb sum = Rgb::Zero(), variance = Rgb::Zero();
  for (int batch = 1;; ++batch) {
    const uint64_t seed = point + (static_cast<uint64_t>(batch - 1) << 32);
    const PathTraceEstimate e = tracer.irradiance(p.x, p.n, paths, seed);
    sum += e.mean;
    variance += e.standard_error.cwiseAbs2();
    const Rgb mean = sum / batch;
    const Rgb error = variance.cwiseSqrt() / batch;
    bool met = true;
    for (int c = 0; c < 3; ++c) met = met && error[c] <= target * std::abs(mean[c]);
    if (target <= 0 || met || batch == max_batches) return {mean, error};
  }
}

/// The points of `file`, read on the root and sent to every process of `job`.
std::vector<ProbePoint> read_points_everywhere(const Job& job, const std::string& file) {
  std::vector<ProbePoint> points;
  job.step([&] {
    if (job.is_root()) points = read_points_csv(file);
  });
  if (!job.distributed()) return points;
  PackedBytes out;
  for (const ProbePoint& p : points) out.put_each(p.x), out.put_each(p.n);
  const std::string bytes = job.broadcast(out.take());
  PackedBytes in(bytes);
  points.resize(bytes.size() / (6 * sizeof(double)));
  for (ProbePoint& p : points) in.get_each(p.x), in.get_each(p.n);
  return points;
}

void run_probe(const ProbeOptions& o) {
  if (o.target_error > 0 && o.method != "pathtrace")
    throw InputError("--target-error is for --method pathtrace");
  if (o.method == "pathtrace" && !o.solution.empty())
    throw InputError("--method pathtrace traces the scene itself: it takes no --solution");
  if (o.method == "montecarlo" && o.solution.empty())
    throw InputError("--method montecarlo needs --solution (a .vtp written by `radiosity solve`)");
  const auto start = std::chrono::steady_clock::now();
  const ThreadLimit limit(o.threads);
  // Over an MPI job: the inputs and the points read on the root and sent to all, runs of points
  // handed out as processes free up (distributed/job.h).
  const Job& job = Job::world();
  const Inputs inputs = load_inputs(job, o.scene, o.solution);
  const Scene& scene = inputs.scene;
  const std::vector<ProbePoint> points = read_points_everywhere(job, o.points);
  std::vector<Rgb> irradiance(points.size());
  std::vector<double> bound(points.size(), 0.0);  // exact: no error to bound
  std::vector<Rgb> standard_error;                // the path tracer's
  // 000 §4: light refracted through transparent polyhedra, the heuristic part, kept apart.
  bool refracts = false;
  for (const Polygon& p : scene.polygons)
    refracts = refracts || scene.materials[p.material].refracts();
  refracts = refracts && scene.refraction_depth > 0;
  std::vector<Rgb> refracted(refracts ? points.size() : 0, Rgb::Zero());
  // 003: light from point sources by way of glossy surfaces, the other heuristic part.
  bool glossy = false;
  for (const Polygon& p : scene.polygons)
    glossy = glossy || scene.materials[p.material].is_glossy();
  std::vector<Rgb> glossy_part(glossy ? points.size() : 0, Rgb::Zero());
  std::function<void(size_t)> gather;
  // The path tracer of the scene itself: no solution, every bounce sampled.
  std::optional<PathTracer> path_tracer;
  // Only the chosen method is built (vertex tracing precomputes interpenetrations).
  const Method method = parse_method(o.method).value_or(Method::montecarlo);
  std::unique_ptr<ExactGatherer> direct;
  std::optional<LocalPass> pass;
  std::optional<MonteCarloGatherer> monte_carlo;
  // Built on every process; a failure on one fails on all (Job::step).
  job.step([&] {
    if (o.method == "pathtrace") {
      path_tracer.emplace(scene, !o.no_interface_reflections);
      standard_error.assign(points.size(), Rgb::Zero());
      gather = [&](size_t i) {
        const PathTraceEstimate e =
            traced_to_target(*path_tracer, points[i], o.samples, o.target_error, i);
        irradiance[i] = e.mean;
        standard_error[i] = e.standard_error;
        bound[i] = std::numeric_limits<double>::infinity();  // sampled: nothing certified (empty)
      };
    } else if (inputs.solution) {
      const Solution& solution = *inputs.solution;
      if (!is_exact(method)) {
        monte_carlo.emplace(scene, faces_from_solution(scene, solution));
        gather = [&](size_t i) {
          irradiance[i] = monte_carlo->gather(points[i].x, points[i].n, o.samples, i);
          bound[i] = std::numeric_limits<double>::infinity();  // sampled: nothing certified (empty)
        };
      } else {
        pass.emplace(scene, faces_from_solution(scene, solution), method, o.settings);
        gather = [&](size_t i) {
          const LocalPassResult r = pass->gather(points[i].x, points[i].n, o.tolerance);
          irradiance[i] = r.irradiance;
          bound[i] = r.bound.maxCoeff();
          if (refracts) refracted[i] = r.refracted;
          if (glossy) glossy_part[i] = r.glossy;
        };
      }
    } else {
      // Both exact methods see the same faces (the polygons, concave ones as triangles). With
      // mirrors, refraction, point lights or glossy surfaces, the local pass at tolerance 0 (it
      // unfolds mirrors and refraction: specular/mirror_images.h, refraction_images.h; adds the
      // lights and the glossy beams).
      bool mirrors = false;
      for (const Polygon& p : scene.polygons)
        mirrors = mirrors || scene.materials[p.material].is_mirror();
      if ((mirrors && scene.mirror_depth > 0) || refracts || glossy || !scene.lights.empty()) {
        pass.emplace(scene, faces_from_polygons(scene), method, o.settings);
        gather = [&](size_t i) {
          const LocalPassResult r = pass->gather(points[i].x, points[i].n, 0);
          irradiance[i] = r.irradiance;
          if (refracts) refracted[i] = r.refracted;
          if (glossy) glossy_part[i] = r.glossy;
        };
      } else {
        direct = make_exact_gatherer(method, scene, faces_from_polygons(scene));
        gather = [&](size_t i) {
          irradiance[i] = exact_irradiance(*direct, points[i].x, points[i].n);
        };
      }
    }
  });

  ProgressBar bar("probe");
  std::atomic<size_t> done{0};
  // Each point is independent and written to its own slot: output order and values do not
  // depend on the thread count, nor on the processes of an MPI job.
  if (!job.distributed()) {
    tbb::parallel_for(size_t(0), points.size(), [&](size_t i) {
      gather(i);
      const size_t finished = ++done;
      if (finished % 256 == 0)
        bar.update(static_cast<double>(finished) / points.size(),
                   std::to_string(finished) + " points");
    });
  } else {
    // Runs of points, 8 a process or more, as the tiles of a render (render/irradiance_render.h).
    const size_t run = std::max<size_t>(1, points.size() / (8 * static_cast<size_t>(job.size())));
    std::vector<std::vector<Rgb>*> columns{&irradiance};
    for (std::vector<Rgb>* c : {&standard_error, &refracted, &glossy_part})
      if (!c->empty()) columns.push_back(c);
    BlockWork work;
    work.blocks = (points.size() + run - 1) / run;
    const auto range = [&](size_t b) {
      return tbb::blocked_range<size_t>(b * run, std::min(points.size(), (b + 1) * run));
    };
    work.compute = [&](size_t b) {
      tbb::parallel_for(range(b), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) gather(i);
      });
    };
    work.pack = [&](size_t b) {
      PackedBytes bytes;
      for (size_t i = range(b).begin(); i != range(b).end(); ++i) {
        for (const std::vector<Rgb>* c : columns) bytes.put_each((*c)[i]);
        bytes.put(bound[i]);
      }
      return bytes.take();
    };
    work.unpack = [&](size_t b, std::string_view data) {
      PackedBytes bytes(data);
      for (size_t i = range(b).begin(); i != range(b).end(); ++i) {
        for (std::vector<Rgb>* c : columns) bytes.get_each((*c)[i]);
        bytes.get(bound[i]);
      }
      if (!bytes.at_end()) throw Error("probe: a run of points came back with the wrong size");
    };
    work.progress = [&](size_t blocks) {
      const size_t finished = std::min(points.size(), blocks * run);
      bar.update(static_cast<double>(finished) / points.size(),
                 std::to_string(finished) + " points");
    };
    job.run_blocks(work);
    if (!job.is_root()) return;
  }
  bar.finish();

  const std::vector<Rgb>* errors = path_tracer ? &standard_error : nullptr;
  // The path tracer follows refraction exactly: its E is the whole. Monte Carlo's rays too.
  std::vector<ApartColumns> apart;
  if (refracts && pass) apart.push_back({"refracted", &refracted});
  // The path tracer follows glossy lobes itself; Monte Carlo takes glossy surfaces as mirrors.
  if (glossy && pass) apart.push_back({"glossy", &glossy_part});
  if (o.output.empty()) {
    write_probe_csv(std::cout, points, irradiance, bound, errors, apart);
  } else {
    write_text_file(o.output, [&](std::ostream& file) {
      write_probe_csv(file, points, irradiance, bound, errors, apart);
    });
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string what =
      path_tracer
          ? "the scene path-traced, " + std::to_string(o.samples) + " paths a point" +
                (o.target_error > 0
                     ? " a batch, to a relative standard error of " + std::to_string(o.target_error)
                     : "")
      : o.solution.empty() ? "direct only"
                           : "from " + o.solution + " at tolerance " + std::to_string(o.tolerance);
  std::cerr << "probe: " << points.size() << " points, " << o.method << ", " << what << ", "
            << seconds << " s" << (o.output.empty() ? "" : "; wrote " + o.output) << "\n";
}

}  // namespace

void add_probe_command(CLI::App& app, Run& run) {
  auto o = std::make_shared<ProbeOptions>();
  CLI::App* sub = app.add_subcommand(
      "probe",
      "Exact irradiance at points (CSV in, CSV out). Without --solution, direct only: "
      "polygons radiate their emission, every polygon occludes from both sides. With "
      "--solution, every element radiates its radiosity (the local pass).");
  sub->footer(
      "Reads rows x,y,z,nx,ny,nz (a header row, blank lines and # comments allowed; the normal is\n"
      "normalized); writes x,y,z,nx,ny,nz,E_r,E_g,E_b,bound: irradiance in W/m^2 and the certified "
      "bound\n"
      "on its error (largest channel: 0 when exact, empty for Monte Carlo), each number in the "
      "shortest\n"
      "form that reads back exactly. A point on a polygon, an edge or a vertex is valid. Parallel "
      "over\n"
      "points (under mpirun, runs of points over the processes: docs/cluster.md); the output is\n"
      "byte-identical for any thread and process count. With refracting materials "
      "(\"ior\"),\n"
      "three more columns refracted_r,refracted_g,refracted_b: the light refracted through them by "
      "the\n"
      "apparent-depth heuristic of paper 000 section 4, NOT in E and NOT covered by the bound (the "
      "total\n"
      "is E + refracted). The path tracer and Monte Carlo follow refraction exactly, in E. With\n"
      "glossy materials (\"gloss\"), three more: glossy_r,glossy_g,glossy_b, the light of point\n"
      "sources reflected by them onto the point (paper 003's beams), also NOT in E and NOT\n"
      "covered by the bound; the path tracer follows the lobes itself, in E.");
  sub->add_option("scene", o->scene, "Scene file (JSON)")->required();
  sub->add_option("-p,--points", o->points,
                  "Points file: rows x,y,z,nx,ny,nz (a header row is allowed)")
      ->required();
  sub->add_option(
         "-m,--method", o->method,
         "hemisphere: exact projection onto the hemisphere (paper 004); vertex: vertex tracing "
         "with "
         "angular spans (paper 001). Both exact; they agree to 1e-9. montecarlo (with --solution): "
         "--samples cosine-weighted rays per point, bound left empty. pathtrace (no --solution): "
         "the scene itself path-traced, every bounce sampled, --samples paths per point, the "
         "reference; adds columns se_r,se_g,se_b (standard errors), bound left empty")
      ->check(CLI::IsMember(probe_method_names()))
      ->capture_default_str();
  add_solution_option(sub, &o->solution, ": gather from its elements");
  add_refraction_options(sub, &o->settings);
  add_glossy_options(sub, &o->settings);
  sub->add_flag("--no-interface-reflections", o->no_interface_reflections,
                "pathtrace: drop the light refracting interfaces reflect (Fresnel, total internal "
                "reflection), the model of the local pass's refraction heuristic (paper 000 "
                "section 4): its reference, where the default is the physics'");
  add_tolerance_option(
      sub, &o->tolerance,
      "With --solution: stop once the certified error bound is at most this fraction of the "
      "value (0: exact); the bound column reports it");
  add_samples_option(sub, &o->samples, "point");
  sub->add_option("--target-error", o->target_error,
                  "pathtrace: trace batches of --samples paths until every channel's standard "
                  "error is at most this fraction of its value (at most " +
                      std::to_string(max_batches) + " batches; 0: one batch)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  sub->add_option("-o,--output", o->output,
                  "Output CSV (default: stdout): x,y,z,nx,ny,nz,E_r,E_g,E_b,bound");
  add_threads_option(sub, &o->threads);
  sub->callback([o, &run] { run = [o] { run_probe(*o); }; });
}

}  // namespace rad::cli
