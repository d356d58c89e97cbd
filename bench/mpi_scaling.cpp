// Issue 21's scaling model: what the MPI render costs on this machine, and from those costs what
// it would do on 8 to 512 processes. Three modes (bench/mpi_scaling.sh runs them):
//
//   mpi_scaling costs SCENE SOLUTION WIDTH HEIGHT TOLERANCE OUT.csv
//       Per-pixel seconds of the local pass (one thread: the ray to the visible point and the
//       gather), the costs the tiles are made of.
//   mpirun -n P mpi_scaling overhead BYTES
//       Through distributed/job.h itself: (1) the time a worker's block costs beyond its work
//       (blocks that sleep 2 ms: sleeping takes no core, so 4 processes on 2 cores measure the
//       messages, not the contention); (2) the root's time per block when it does nothing but
//       serve (workers' blocks empty); (3) broadcasting BYTES (the inputs). One CSV line.
//   mpi_scaling model COSTS.csv OVERHEAD.csv MEASURED.csv WIDTH HEIGHT CORES OUT.md CHART.png
//       Simulates the dynamic schedule of render/irradiance_render.cpp (tiles of 64 pixels
//       halved to 16 until 8 a process; each process takes the next tile when free; the root
//       computes tiles on a thread and serves the others, one message at a time) with the
//       measured costs, checks it against the times measured with 1 to 4 processes on this
//       machine's CORES cores (processes beyond them share: their tiles take P / CORES longer),
//       and predicts speed-up and efficiency for 8 to 512 processes of a core each, for the
//       measured image and for one 16 x 16 times larger (each pixel's cost spread over the 256
//       pixels it becomes: the same scene at a production size). The pixel costs are scaled to
//       the one-process render's measured time (the render shades and follows the eye ray
//       besides gathering).
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <queue>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "distributed/job.h"
#include "formats/solution_io.h"
#include "localpass/local_pass.h"
#include "radiosity/solution_faces.h"
#include "render/irradiance_render.h"
#include "scene/camera.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "viz/charts.h"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

int costs(int argc, char** argv) {
  if (argc < 8) return 2;
  using namespace rad;
  const Scene scene = load_scene(argv[2]);
  const Solution solution = read_solution(argv[3]);
  const int width = std::stoi(argv[4]), height = std::stoi(argv[5]);
  const double tolerance = std::stod(argv[6]);
  const LocalPass pass(scene, faces_from_solution(scene, solution), Method::hemisphere);
  CameraSpec spec = *scene.camera;
  spec.width = width;
  spec.height = height;
  const Camera camera(spec);
  const RayCaster caster(scene);
  std::ofstream out(argv[7]);
  out << "x,y,seconds\n";
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const auto start = Clock::now();
      const auto hit = caster.closest_hit(camera.ray(x + 0.5, y + 0.5));
      if (hit && hit->front_facing) (void)pass.gather(hit->point, hit->normal, tolerance);
      out << x << ',' << y << ',' << since(start) << '\n';
    }
  return 0;
}

/// Seconds of Job::run_blocks over `blocks` blocks whose work is `work(rank)` seconds of sleep,
/// each block's result `bytes` long; `gap`, if given, gets the root's mean time between two
/// results it unpacked (its rate of serving).
double time_blocks(const rad::Job& job, size_t blocks, const std::function<double(int)>& work,
                   size_t bytes, double* gap = nullptr) {
  rad::BlockWork w;
  w.blocks = blocks;
  const double seconds = work(job.rank());
  w.compute = [&](size_t) {
    // On the root this runs on its worker thread: the root's own share.
    if (seconds > 0) std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  };
  w.pack = [&](size_t) { return std::string(bytes, 'x'); };
  Clock::time_point first, last;
  size_t unpacked = 0;
  w.unpack = [&](size_t, std::string_view) {
    last = Clock::now();
    if (unpacked++ == 0) first = last;
  };
  job.run_blocks(w);  // warm-up
  unpacked = 0;
  const auto start = Clock::now();
  job.run_blocks(w);
  if (gap && unpacked > 1)
    *gap = std::chrono::duration<double>(last - first).count() / (unpacked - 1);
  return since(start);
}

int overhead(int argc, char** argv) {
  if (argc < 3) return 2;
  const rad::Job job(&argc, &argv);
  const size_t bytes = std::stoul(argv[2]);
  const int p = job.size();
  // A 16 x 16 tile's result: 4 RGB images in doubles, three counts and a flag a pixel.
  const size_t tile_bytes = 16 * 16 * (12 * sizeof(double) + 3 * sizeof(int) + 1);
  // (1) Every process sleeps 2 ms a block: the time beyond B x 2 ms / P is the messages'.
  const size_t blocks = 200;
  const double sleep = 0.002;
  const double t1 = time_blocks(
      job, blocks, [&](int) { return sleep; }, tile_bytes);
  const double per_block_overhead = std::max(0.0, t1 * p / blocks - sleep);
  // (2) The root's worker sleeps long (it takes one block); the others' blocks are empty: the
  // root serves one message after another, and the time per block is its service time.
  double service = 0;
  if (p > 1)
    time_blocks(
        job, 2000, [](int rank) { return rank == 0 ? 0.2 : 0.0; }, tile_bytes, &service);
  // (3) The inputs' broadcast.
  std::string payload(job.is_root() ? bytes : 0, 'x');
  MPI_Barrier(MPI_COMM_WORLD);
  auto start = Clock::now();
  for (int i = 0; i < 5; ++i) payload = job.broadcast(job.is_root() ? std::string(bytes, 'x') : "");
  MPI_Barrier(MPI_COMM_WORLD);
  const double broadcast = since(start) / 5;
  if (job.is_root())
    std::printf("%d,%.9g,%.9g,%.9g,%zu\n", p, per_block_overhead, service, broadcast, bytes);
  return 0;
}

struct Overhead {
  int processes;
  double per_block, service, broadcast;
};

std::vector<std::vector<double>> read_csv(const std::string& file) {
  std::ifstream in(file);
  std::string line;
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    if (line.empty() || !(std::isdigit(static_cast<unsigned char>(line[0])) || line[0] == '-'))
      continue;
    std::vector<double> row;
    std::stringstream s(line);
    std::string field;
    while (std::getline(s, field, ',')) row.push_back(std::stod(field));
    rows.push_back(row);
  }
  return rows;
}

/// The schedule's makespan: tiles in order to whichever process is free first; process 0's
/// worker thread pays nothing beyond the work, the others `per_block` a tile and one `service`
/// of the root's single server each (queued when it is busy).
double makespan(const std::vector<double>& tiles, int processes, double per_block, double service) {
  using Event = std::pair<double, int>;  // (free at, process)
  std::priority_queue<Event, std::vector<Event>, std::greater<>> free;
  for (int p = 0; p < processes; ++p) free.push({0.0, p});
  double server = 0, end = 0;
  for (const double cost : tiles) {
    auto [t, p] = free.top();
    free.pop();
    double done = t + cost;
    if (p != 0) {
      const double served = std::max(server, done) + service;  // its result, and the next tile
      server = served;
      done = served + per_block;
    }
    end = std::max(end, done);
    free.push({done, p});
  }
  return end;
}

std::vector<double> tile_costs(const std::vector<double>& pixel, int width, int height, int side) {
  std::vector<double> out;
  for (int y0 = 0; y0 < height; y0 += side)
    for (int x0 = 0; x0 < width; x0 += side) {
      double c = 0;
      for (int y = y0; y < std::min(y0 + side, height); ++y)
        for (int x = x0; x < std::min(x0 + side, width); ++x) c += pixel[y * width + x];
      out.push_back(c);
    }
  return out;
}

int model(int argc, char** argv) {
  if (argc < 10) return 2;
  const auto cost_rows = read_csv(argv[2]);
  const auto overhead_rows = read_csv(argv[3]);
  const auto measured_rows = read_csv(argv[4]);  // processes, seconds (median), setup seconds
  const int width = std::stoi(argv[5]), height = std::stoi(argv[6]);
  const int cores = std::stoi(argv[7]);
  std::vector<double> pixel(static_cast<size_t>(width) * height, 0);
  for (const auto& r : cost_rows) pixel[static_cast<size_t>(r[1]) * width + r[0]] = r[2];
  double gathering = 0;
  for (double c : pixel) gathering += c;
  // Calibration: the one-process render's time beyond its setup, against the gathers' sum.
  double setup = 0, one_process = 0;
  for (const auto& r : measured_rows)
    if (r[0] == 1 && r.size() > 2) setup = r[2], one_process = r[1];
  const double calibration = one_process > setup ? (one_process - setup) / gathering : 1;
  for (double& c : pixel) c *= calibration;
  const double work = gathering * calibration;
  // The 16 x 16 times larger image: each pixel becomes 256, each a 256th of the cost.
  constexpr int kScale = 16;
  const int big_w = kScale * width, big_h = kScale * height;
  std::vector<double> big(static_cast<size_t>(big_w) * big_h);
  for (int y = 0; y < big_h; ++y)
    for (int x = 0; x < big_w; ++x)
      big[y * big_w + x] = pixel[(y / kScale) * width + x / kScale] / (kScale * kScale);

  std::vector<Overhead> overheads;
  for (const auto& r : overhead_rows)
    overheads.push_back({static_cast<int>(r[0]), r[1], r[2], r[3]});
  // Measured at 2 to 4 processes: the largest per-block time (the oversubscribed runs are the
  // slowest); the root's service time bounded by the shortest gap between results it served
  // (with one worker the gap is that worker's round trip; with more, the root is the limit);
  // the broadcast as a tree, a + b log2 P, fitted by least squares.
  double per_block = 0, service = 1e9;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (const Overhead& o : overheads) {
    if (o.processes < 2) continue;
    per_block = std::max(per_block, o.per_block);
    if (o.service > 0) service = std::min(service, o.service);
    const double x = std::log2(o.processes);
    sx += x, sy += o.broadcast, sxx += x * x, sxy += x * o.broadcast, ++n;
  }
  if (service == 1e9) service = 0;
  const double slope = n > 1 ? (n * sxy - sx * sy) / std::max(1e-30, n * sxx - sx * sx) : 0;
  const double intercept = n > 0 ? (sy - slope * sx) / n : 0;
  const auto broadcast = [&](int p) {
    return p < 2 ? 0.0 : std::max(0.0, intercept + slope * std::log2(p));
  };
  // `share`: how much longer a tile takes than alone on a core (processes sharing cores).
  const auto predict = [&](const std::vector<double>& px, int w, int h, int p, double share) {
    const int side = rad::tile_side(w, h, p);
    // With more than one process every other process parses what the root sent and builds its
    // own pass after the broadcast: the setup twice, plus the broadcast.
    const double start = p == 1 ? setup : 2 * setup + broadcast(p);
    std::vector<double> tiles = tile_costs(px, w, h, side);
    for (double& t : tiles) t *= share;
    return start + makespan(tiles, p, per_block, service);
  };

  std::ofstream md(argv[8]);
  char text[600];
  std::snprintf(text, sizeof text,
                "Model inputs, measured on this machine: %d x %d pixels, %.1f s of local pass in "
                "all on one thread (the gathers' %.1f s times %.3f, the render's own share), "
                "setup %.2f s; a worker's tile costs %.2f ms beyond its work, the root %.0f us "
                "a tile served; broadcasting the inputs takes %.2f + %.2f log2(P) ms.\n\n",
                width, height, work, gathering, calibration, setup, per_block * 1e3, service * 1e6,
                intercept * 1e3, slope * 1e3);
  md << text;
  md << "The model against the render measured here (median of 3 runs; " << cores
     << " cores: more processes share them):\n\n";
  md << "| processes | measured (s) | model (s) | model/measured |\n|---|---|---|---|\n";
  for (const auto& r : measured_rows) {
    const int p = static_cast<int>(r[0]);
    const double m = predict(pixel, width, height, p, std::max(1.0, double(p) / cores));
    std::snprintf(text, sizeof text, "| %d | %.2f | %.2f | %.2f |\n", p, r[1], m, m / r[1]);
    md << text;
  }
  md << "\nPredicted for processes of a core each (a cluster), the measured image and the same "
        "scene "
     << kScale << " x " << kScale << " times larger:\n\n";
  md << "| processes | speed-up, " << width << "x" << height << " | efficiency | speed-up, "
     << big_w << "x" << big_h
     << " | efficiency | tiles a process (large) |\n|---|---|---|---|---|---|\n";
  rad::LineChart chart;
  chart.title = "MPI render: modelled speed-up (measured costs)";
  chart.x_label = "processes";
  chart.y_label = "speed-up over one process";
  chart.log_x = chart.log_y = true;
  chart.legend = rad::LineChart::Corner::top_left;
  rad::ChartSeries small{std::to_string(width) + "x" + std::to_string(height), {}, {}};
  rad::ChartSeries large{std::to_string(big_w) + "x" + std::to_string(big_h), {}, {}};
  rad::ChartSeries ideal{"ideal", {}, {}};
  const double t1_small = predict(pixel, width, height, 1, 1);
  const double t1_large = predict(big, big_w, big_h, 1, 1);
  for (int p = 1; p <= 512; p *= 2) {
    const double s = t1_small / predict(pixel, width, height, p, 1);
    const double l = t1_large / predict(big, big_w, big_h, p, 1);
    const int side = rad::tile_side(big_w, big_h, p);
    const double tiles = std::ceil(big_w / double(side)) * std::ceil(big_h / double(side));
    std::snprintf(text, sizeof text, "| %d | %.1f | %.0f%% | %.1f | %.0f%% | %.1f |\n", p, s,
                  100 * s / p, l, 100 * l / p, tiles / p);
    md << text;
    small.x.push_back(p), small.y.push_back(s);
    large.x.push_back(p), large.y.push_back(l);
    ideal.x.push_back(p), ideal.y.push_back(p);
  }
  chart.series = {ideal, small, large};
  rad::write_chart_png(argv[9], chart);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "costs") return costs(argc, argv);
  if (mode == "overhead") return overhead(argc, argv);
  if (mode == "model") return model(argc, argv);
  std::cerr << "usage: mpi_scaling costs|overhead|model ... (see the comment at the top)\n";
  return 2;
}
