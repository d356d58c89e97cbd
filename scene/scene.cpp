#include "scene/scene.h"

#include <cstdint>
#include <cstdio>
#include <numbers>

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

Rgb Scene::light_power() const {
  Rgb power = Rgb::Zero();
  for (const PointLight& light : lights) power += 4 * std::numbers::pi * light.intensity;
  return power;
}

int Scene::emitter_count() const {
  int count = 0;
  for (const Polygon& p : polygons) count += materials[p.material].is_emitter() ? 1 : 0;
  return count;
}

std::string Scene::fingerprint() const {
  uint64_t hash = 0xcbf29ce484222325ull;
  auto add = [&hash](const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 0x100000001b3ull;
  };
  for (const Polygon& p : polygons) {
    for (const Vec3& v : p.vertices) add(v.data(), 3 * sizeof(double));
    const Material& m = materials[p.material];
    add(m.reflectance.data(), 3 * sizeof(double));
    add(m.emission.data(), 3 * sizeof(double));
    // Filters and mirrors change the solution too; opaque diffuse scenes keep the fingerprint
    // they had before these keys existed.
    if (m.is_filter()) add(m.transmittance.data(), 3 * sizeof(double));
    if (m.is_mirror()) add(m.specular.data(), 3 * sizeof(double));
    if (m.refracts()) {
      const Refraction& r = *m.refraction;
      add(r.ior.data(), 3 * sizeof(double));
      add(r.transmittance.data(), 3 * sizeof(double));
      add(r.attenuation.data(), 3 * sizeof(double));
      const char fresnel = r.fresnel;
      add(&fresnel, 1);
    }
  }
  for (const PointLight& light : lights) {  // none: the fingerprint of before lights existed
    add(light.position.data(), 3 * sizeof(double));
    add(light.intensity.data(), 3 * sizeof(double));
  }
  if (mirror_depth != kDefaultMirrorDepth) add(&mirror_depth, sizeof(mirror_depth));
  if (refraction_depth != kDefaultRefractionDepth) add(&refraction_depth, sizeof(refraction_depth));
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

int Scene::vertex_count() const {
  int count = 0;
  for (const Polygon& p : polygons) count += static_cast<int>(p.vertices.size());
  return count;
}

}  // namespace rad
