#include "scene/scene.h"

namespace rad {

std::string Scene::describe_polygon(int polygon) const {
  const Polygon& p = polygons.at(polygon);
  std::string text = "objects[" + std::to_string(p.object) + "]";
  if (p.object >= 0 && p.object < static_cast<int>(objects.size()) &&
      !objects[p.object].name.empty()) {
    text += " \"" + objects[p.object].name + "\"";
  }
  text += objects.empty() || objects[p.object].mesh.empty() ? " polygon " : " face ";
  text += std::to_string(p.source_index);
  if (p.triangle >= 0) text += " triangle " + std::to_string(p.triangle);
  return text;
}

Bounds Scene::bounds() const {
  Bounds b;
  for (const Polygon& p : polygons) {
    for (const Vec3& v : p.vertices) b.add(v);
  }
  return b;
}

double Scene::total_area() const {
  double area = 0;
  for (const Polygon& p : polygons) area += p.area;
  return area;
}

Rgb Scene::emitted_power() const {
  Rgb power = Rgb::Zero();
  for (const Polygon& p : polygons) power += materials[p.material].emission * p.area;
  return power;
}

int Scene::emitter_count() const {
  int count = 0;
  for (const Polygon& p : polygons) count += materials[p.material].is_emitter() ? 1 : 0;
  return count;
}

int Scene::vertex_count() const {
  int count = 0;
  for (const Polygon& p : polygons) count += static_cast<int>(p.vertices.size());
  return count;
}

}  // namespace rad
