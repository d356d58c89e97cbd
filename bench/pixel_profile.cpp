// Per-pixel counters of the local pass on a saved solution (one thread): where the work goes.
// Usage: pixel_profile SCENE SOLUTION SIZE TOLERANCE [METHOD] [VISIBLE_SET_FROM]
// (VISIBLE_SET_FROM: LocalPassSettings::visible_set_from; a huge number turns the visibility
// culling off.)
#include <chrono>
#include <cstdio>
#include <string>

#include "formats/solution_io.h"
#include "localpass/local_pass.h"
#include "radiosity/solution_faces.h"
#include "scene/camera.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"

int main(int argc, char** argv) {
  using namespace rad;
  if (argc < 5) return 2;
  const Scene scene = load_scene(argv[1]);
  const Solution solution = read_solution(argv[2]);
  const int size = std::stoi(argv[3]);
  const double tolerance = std::stod(argv[4]);
  const Method method = *parse_method(argc > 5 ? argv[5] : "hemisphere");
  const auto t0 = std::chrono::steady_clock::now();
  LocalPassSettings settings;
  if (argc > 6) settings.visible_set_from = std::stoi(argv[6]);
  const LocalPass pass(scene, faces_from_solution(scene, solution), method, settings);
  const auto t1 = std::chrono::steady_clock::now();
  CameraSpec spec = *scene.camera;
  spec.width = spec.height = size;
  const Camera camera(spec);
  const RayCaster caster(scene);
  double clusters = 0, exact = 0, unoccluded = 0, gathers = 0, projected = 0, visible = 0,
         pixels = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const auto hit = caster.closest_hit(camera.ray(x + 0.5, y + 0.5));
      if (!hit || !hit->front_facing) continue;
      const LocalPassResult r = pass.gather(hit->point, hit->normal, tolerance);
      clusters += r.clusters, exact += r.gathered_exactly, unoccluded += r.unoccluded;
      gathers += r.gathers, projected += r.projected, visible += r.visible_polygons, ++pixels;
    }
  const auto t2 = std::chrono::steady_clock::now();
  const double build = std::chrono::duration<double>(t1 - t0).count();
  const double run = std::chrono::duration<double>(t2 - t1).count();
  std::printf(
      "build %.3f s; %g pixels, %.1f us/pixel; per pixel: clusters %.1f, exact %.1f "
      "(unoccluded %.1f), gathers %.2f, projected %.1f, polygons it may see %.1f of %zu\n",
      build, pixels, 1e6 * run / pixels, clusters / pixels, exact / pixels, unoccluded / pixels,
      gathers / pixels, projected / pixels, visible / pixels, scene.polygons.size());
}
