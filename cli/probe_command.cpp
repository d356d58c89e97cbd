// `radiosity probe SCENE --points P.csv [--method hemisphere|vertex] [-o OUT.csv]`: exact irradiance
// at given points, direct lighting only (polygons radiate their emission, all occlude).
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/common.h"
#include "localpass/hemisphere_gather.h"
#include "localpass/vertex_tracing.h"
#include "scene/error.h"
#include "viz/atomic_file.h"
#include "viz/points_csv.h"

namespace rad::cli {
namespace {

struct ProbeOptions {
  std::string scene;
  std::string points;
  std::string method = "hemisphere";
  std::string output;  ///< empty: stdout
  int threads = 0;
};

void run_probe(const ProbeOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const ThreadLimit limit(o.threads);
  const Scene scene = load_scene_reporting(o.scene);
  const std::vector<ProbePoint> points = read_points_csv(o.points);
  // Both exact methods see the same faces (the polygons, concave ones as triangles).
  // Only the chosen one is built (vertex tracing precomputes interpenetrations).
  std::optional<HemisphereGatherer> hemisphere;
  std::optional<VertexTracer> tracer;
  if (o.method == "vertex") {
    tracer.emplace(scene);
  } else {
    hemisphere.emplace(scene);
  }

  std::vector<Rgb> irradiance(points.size());
  std::vector<double> bound(points.size(), 0.0);  // exact: no error to bound
  ProgressBar bar("probe");
  std::atomic<size_t> done{0};
  // Each point is independent and written to its own slot: output order and values do not
  // depend on the thread count.
  tbb::parallel_for(size_t(0), points.size(), [&](size_t i) {
    irradiance[i] = tracer ? tracer->gather(points[i].x, points[i].n).irradiance
                           : hemisphere->gather(points[i].x, points[i].n).irradiance;
    const size_t finished = ++done;
    if (finished % 256 == 0) bar.update(static_cast<double>(finished) / points.size(), std::to_string(finished) + " points");
  });
  bar.finish();

  if (o.output.empty()) {
    write_probe_csv(std::cout, points, irradiance, bound);
  } else {
    AtomicFile out(o.output);
    {
      std::ofstream file(out.temp_path());
      write_probe_csv(file, points, irradiance, bound);
      if (!file.flush()) throw Error(o.output + ": cannot write");
    }
    out.commit();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cerr << "probe: " << points.size() << " points, " << o.method << ", direct only, " << seconds << " s"
            << (o.output.empty() ? "" : "; wrote " + o.output) << "\n";
}

}  // namespace

void add_probe_command(CLI::App& app, Run& run) {
  auto o = std::make_shared<ProbeOptions>();
  CLI::App* sub = app.add_subcommand("probe",
                                     "Exact irradiance at points (CSV in, CSV out). Direct only: polygons radiate their "
                                     "emission, every polygon occludes from both sides.");
  sub->add_option("scene", o->scene, "Scene file (JSON)")->required();
  sub->add_option("-p,--points", o->points, "Points file: rows x,y,z,nx,ny,nz (a header row is allowed)")->required();
  sub->add_option("-m,--method", o->method,
                  "hemisphere: exact projection onto the hemisphere (paper 004); vertex: vertex tracing with "
                  "angular spans (paper 001). Both exact; they agree to 1e-9")
      ->check(CLI::IsMember({"hemisphere", "vertex"}))
      ->capture_default_str();
  sub->add_option("-o,--output", o->output, "Output CSV (default: stdout): x,y,z,nx,ny,nz,E_r,E_g,E_b,bound");
  sub->add_option("-j,--threads", o->threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 1024));
  sub->callback([o, &run] { run = [o] { run_probe(*o); }; });
}

}  // namespace rad::cli
