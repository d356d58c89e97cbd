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
#include "cli/methods.h"
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

/// The bound of a sampled value: nothing certified (an empty column).
constexpr double kSampled = std::numeric_limits<double>::infinity();

/// What a probe computes, one slot a point: E, the bound (largest channel), and the columns
/// only some methods and scenes have (empty otherwise).
struct ProbeColumns {
  std::vector<Rgb> irradiance;
  std::vector<double> bound;        ///< 0: exact; infinity: sampled, nothing certified
  std::vector<Rgb> standard_error;  ///< the path tracer's
  std::vector<Rgb> refracted;       ///< 000 §4's heuristic part, kept apart
  std::vector<Rgb> glossy;          ///< 003's heuristic part, kept apart

  ProbeColumns(size_t points, bool path_traced, bool refracts, bool glossy_surfaces)
      : irradiance(points),
        bound(points, 0.0),
        standard_error(path_traced ? points : 0, Rgb::Zero()),
        refracted(refracts ? points : 0, Rgb::Zero()),
        glossy(glossy_surfaces ? points : 0, Rgb::Zero()) {}
};

/// The gatherers a probe may build; only the chosen method's is (vertex tracing precomputes
/// interpenetrations).
struct ProbeGatherers {
  std::optional<PathTracer> path_tracer;  ///< the scene itself, every bounce sampled
  std::unique_ptr<ExactGatherer> direct;  ///< direct lighting, no specular transfer
  std::optional<LocalPass> pass;
  std::optional<MonteCarloGatherer> monte_carlo;
};

bool any_material(const Scene& scene, bool (Material::*has)() const) {
  for (const Polygon& p : scene.polygons)
    if ((scene.materials[p.material].*has)()) return true;
  return false;
}

/// Builds the chosen method's gatherer into `g` and returns the gather of point i into `out`.
std::function<void(size_t)> point_gather(const ProbeOptions& o, const MethodTraits& m,
                                         const Inputs& inputs,
                                         const std::vector<ProbePoint>& points, ProbeGatherers& g,
                                         ProbeColumns& out) {
  const Scene& scene = inputs.scene;
  const bool refracts = !out.refracted.empty(), glossy = !out.glossy.empty();
  if (m.kind == MethodKind::path_tracer) {
    g.path_tracer.emplace(scene, !o.no_interface_reflections);
    return [&o, &points, &g, &out](size_t i) {
      const PathTraceEstimate e =
          traced_to_target(*g.path_tracer, points[i], o.samples, o.target_error, i);
      out.irradiance[i] = e.mean;
      out.standard_error[i] = e.standard_error;
      out.bound[i] = kSampled;
    };
  }
  // The local pass, for the exact methods: from the solution, or (direct lighting) at
  // tolerance 0 when the scene has mirrors, refraction, point lights or glossy surfaces (it
  // unfolds mirrors and refraction: specular/mirror_images.h, refraction_images.h; adds the
  // lights and the glossy beams).
  const auto local_pass = [&](double tolerance, bool bounded) -> std::function<void(size_t)> {
    return [&points, &g, &out, tolerance, bounded, refracts, glossy](size_t i) {
      const LocalPassResult r = g.pass->gather(points[i].x, points[i].n, tolerance);
      out.irradiance[i] = r.irradiance;
      if (bounded) out.bound[i] = r.bound.maxCoeff();
      if (refracts) out.refracted[i] = r.refracted;
      if (glossy) out.glossy[i] = r.glossy;
    };
  };
  if (inputs.solution) {
    std::vector<EmittingFace> faces = faces_from_solution(scene, *inputs.solution);
    if (!m.exact) {
      g.monte_carlo.emplace(scene, faces);
      return [&o, &points, &g, &out](size_t i) {
        out.irradiance[i] = g.monte_carlo->gather(points[i].x, points[i].n, o.samples, i);
        out.bound[i] = kSampled;
      };
    }
    g.pass.emplace(scene, std::move(faces), *m.local, o.settings);
    return local_pass(o.tolerance, true);
  }
  // Both exact methods see the same faces (the polygons, concave ones as triangles).
  const bool mirrors = any_material(scene, &Material::is_mirror) && scene.mirror_depth > 0;
  if (mirrors || refracts || glossy || !scene.lights.empty()) {
    g.pass.emplace(scene, faces_from_polygons(scene), *m.local, o.settings);
    return local_pass(0, false);
  }
  g.direct = make_exact_gatherer(*m.local, scene, faces_from_polygons(scene));
  return [&points, &g, &out](size_t i) {
    out.irradiance[i] = exact_irradiance(*g.direct, points[i].x, points[i].n);
  };
}

/// Runs `gather` over every point, with a progress bar: in parallel on this machine, or over
/// an MPI job in runs of points, 8 a process or more, as the tiles of a render
/// (render/irradiance_render.h). Each point is independent and written to its own slot: output
/// order and values do not depend on the thread count, nor on the processes. False on a
/// process other than the root of a job (its columns hold only its runs).
bool gather_points(const Job& job, size_t count, const std::function<void(size_t)>& gather,
                   ProbeColumns& out) {
  ProgressBar bar("probe");
  const auto progress = [&](size_t finished) {
    bar.update(static_cast<double>(finished) / count, std::to_string(finished) + " points");
  };
  if (!job.distributed()) {
    std::atomic<size_t> done{0};
    tbb::parallel_for(size_t(0), count, [&](size_t i) {
      gather(i);
      const size_t finished = ++done;
      if (finished % 256 == 0) progress(finished);
    });
    bar.finish();
    return true;
  }
  const size_t run = std::max<size_t>(1, count / (8 * static_cast<size_t>(job.size())));
  std::vector<std::vector<Rgb>*> columns{&out.irradiance};
  for (std::vector<Rgb>* c : {&out.standard_error, &out.refracted, &out.glossy})
    if (!c->empty()) columns.push_back(c);
  BlockWork work;
  work.blocks = (count + run - 1) / run;
  const auto range = [&](size_t b) {
    return tbb::blocked_range<size_t>(b * run, std::min(count, (b + 1) * run));
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
      bytes.put(out.bound[i]);
    }
    return bytes.take();
  };
  work.unpack = [&](size_t b, std::string_view data) {
    PackedBytes bytes(data);
    for (size_t i = range(b).begin(); i != range(b).end(); ++i) {
      for (std::vector<Rgb>* c : columns) bytes.get_each((*c)[i]);
      bytes.get(out.bound[i]);
    }
    if (!bytes.at_end()) throw Error("probe: a run of points came back with the wrong size");
  };
  work.progress = [&](size_t blocks) { progress(std::min(count, blocks * run)); };
  job.run_blocks(work);
  if (!job.is_root()) return false;
  bar.finish();
  return true;
}

/// Writes the CSV to -o or stdout: the heuristic parts apart from E only for the local pass
/// (the path tracer follows refraction and glossy lobes itself, in E; Monte Carlo's rays
/// follow refraction and take glossy surfaces as mirrors).
void write_probe_output(const ProbeOptions& o, const std::vector<ProbePoint>& points,
                        const ProbeColumns& c, const ProbeGatherers& g) {
  const std::vector<Rgb>* errors = g.path_tracer ? &c.standard_error : nullptr;
  std::vector<ApartColumns> apart;
  if (!c.refracted.empty() && g.pass) apart.push_back({"refracted", &c.refracted});
  if (!c.glossy.empty() && g.pass) apart.push_back({"glossy", &c.glossy});
  const auto write = [&](std::ostream& out) {
    write_probe_csv(out, points, c.irradiance, c.bound, errors, apart);
  };
  if (o.output.empty()) {
    write(std::cout);
  } else {
    write_text_file(o.output, write);
  }
}

void run_probe(const ProbeOptions& o) {
  const MethodTraits& m = method_traits(o.method);
  if (o.target_error > 0 && m.kind != MethodKind::path_tracer)
    throw InputError("--target-error is for --method pathtrace");
  check_solution_use(m, !o.solution.empty(), MethodCommand::probe);
  const auto start = std::chrono::steady_clock::now();
  const ThreadLimit limit(o.threads);
  // Over an MPI job: the inputs and the points read on the root and sent to all, runs of points
  // handed out as processes free up (distributed/job.h).
  const Job& job = Job::world();
  const Inputs inputs = load_inputs(job, o.scene, o.solution);
  const Scene& scene = inputs.scene;
  const std::vector<ProbePoint> points = read_points_everywhere(job, o.points);
  job.step([&] {
    if (job.is_root()) check_outputs({{"the output (-o)", o.output}});
  });
  const bool refracts = any_material(scene, &Material::refracts) && scene.refraction_depth > 0;
  ProbeColumns columns(points.size(), m.kind == MethodKind::path_tracer, refracts,
                       any_material(scene, &Material::is_glossy));
  ProbeGatherers gatherers;
  std::function<void(size_t)> gather;
  // Built on every process; a failure on one fails on all (Job::step).
  job.step([&] { gather = point_gather(o, m, inputs, points, gatherers, columns); });
  if (!gather_points(job, points.size(), gather, columns)) return;
  write_probe_output(o, points, columns, gatherers);

  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string what =
      gatherers.path_tracer
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
  sub->add_option("scene", o->scene, kSceneHelp)->required();
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
      ->check(CLI::IsMember(method_names_for(MethodCommand::probe)))
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
      ->check(kFinite)
      ->capture_default_str();
  sub->add_option("-o,--output", o->output,
                  "Output CSV (default or -: stdout): x,y,z,nx,ny,nz,E_r,E_g,E_b,bound");
  add_threads_option(sub, &o->threads);
  sub->callback([o, &run] { run = [o] { run_probe(*o); }; });
}

}  // namespace rad::cli
