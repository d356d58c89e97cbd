#include "render/patch_render.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "radiosity/patch_mesh.h"
#include "scene/ray_caster.h"

namespace rad {

Image render_patches(const Scene& scene, const Solution& solution, const Camera& camera,
                     bool with_ambient) {
  const ElementMesh mesh(solution, scene.tolerance().pad);

  // The elements as a scene of their own, so a primary hit names the element directly.
  Scene elements;
  elements.materials = scene.materials;
  std::vector<Rgb> face_rho;
  std::vector<std::vector<Vec3>> face_points;
  for (int f = 0; f < mesh.face_count(); ++f) {
    const Element& e = solution.elements[mesh.element(f)];
    const Polygon& parent = scene.polygons[e.polygon];
    Polygon p;
    p.vertices = mesh.face_points(f);
    p.normal = parent.normal;
    p.area = e.area;
    p.material = parent.material;
    p.object = parent.object;
    p.source_index = f;
    face_points.push_back(p.vertices);
    face_rho.push_back(scene.materials[parent.material].reflectance);
    elements.polygons.push_back(std::move(p));
  }
  const std::vector<Rgb> vertex_value = mesh.vertex_radiosity(solution, face_rho, with_ambient);
  std::vector<std::vector<Rgb>> face_values(mesh.face_count());
  for (int f = 0; f < mesh.face_count(); ++f) {
    for (const int v : mesh.face_vertices(f)) face_values[f].push_back(vertex_value[v]);
  }
  const RayCaster caster(elements);

  Image image(camera.width(), camera.height());
  tbb::parallel_for(
      tbb::blocked_range<int>(0, image.height), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y) {
          for (int x = 0; x < image.width; ++x) {
            const auto hit = caster.closest_hit(camera.ray(x + 0.5, y + 0.5));
            if (!hit || !hit->front_facing) continue;
            image.at(x, y) = interpolate_mean_value(
                face_points[hit->polygon], face_values[hit->polygon], hit->normal, hit->point);
          }
        }
      });
  return image;
}

}  // namespace rad
