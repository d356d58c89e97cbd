#include "scene/ray_caster.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <limits>
#include <string>

#include "geometry/refraction.h"
#include "geometry/tolerance.h"
#include "scene/error.h"

namespace rad {

struct RayCaster::Impl {
  RTCDevice device = nullptr;
  RTCScene rtc_scene = nullptr;
  std::vector<int> triangle_polygon;  ///< Embree primitive id -> polygon index.
  std::string device_error;

  ~Impl() {
    if (rtc_scene) rtcReleaseScene(rtc_scene);
    if (device) rtcReleaseDevice(device);
  }

  /// Embree reports errors through a callback; keep the last one for the exception message.
  static void record_device_error(void* user, RTCError code, const char* message) {
    auto* impl = static_cast<Impl*>(user);
    impl->device_error =
        "Embree error " + std::to_string(static_cast<int>(code)) + ": " + (message ? message : "");
  }
};

RayCaster::RayCaster(const Scene& scene) : scene_(scene), impl_(std::make_unique<Impl>()) {
  for (const Polygon& p : scene.polygons)
    has_filters_ = has_filters_ || scene.materials[p.material].is_filter();
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw Error("cannot create the Embree device");
  rtcSetDeviceErrorFunction(impl_->device, Impl::record_device_error, impl_.get());

  // Triangulate every polygon in its own plane; Embree sees a triangle soup.
  std::vector<float> positions;
  std::vector<unsigned> indices;
  for (size_t p = 0; p < scene.polygons.size(); ++p) {
    const Polygon& polygon = scene.polygons[p];
    const unsigned base = static_cast<unsigned>(positions.size() / 3);
    for (const Vec3& v : polygon.vertices) {
      positions.insert(positions.end(), {static_cast<float>(v.x()), static_cast<float>(v.y()),
                                         static_cast<float>(v.z())});
    }
    for (const auto& t : triangulate(project_to_plane(polygon.vertices, polygon.normal))) {
      indices.insert(indices.end(), {base + t[0], base + t[1], base + t[2]});
      impl_->triangle_polygon.push_back(static_cast<int>(p));
    }
  }

  impl_->rtc_scene = rtcNewScene(impl_->device);
  // Robust mode keeps Embree's watertight triangle test: no rays slip through shared edges.
  rtcSetSceneFlags(impl_->rtc_scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(impl_->rtc_scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const size_t vertex_count = positions.size() / 3, triangle_count = indices.size() / 3;
  // Embree reads vertex buffers with 16-byte loads: one float of padding at the end.
  auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertex_count + 1));
  auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangle_count));
  if (!vb || !ib) throw Error("cannot allocate Embree buffers: " + impl_->device_error);
  std::copy(positions.begin(), positions.end(), vb);
  std::copy(indices.begin(), indices.end(), ib);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(impl_->rtc_scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(impl_->rtc_scene);
  if (!impl_->device_error.empty())
    throw Error("cannot build the ray-casting scene: " + impl_->device_error);
}

RayCaster::~RayCaster() = default;

namespace {

RTCRay to_embree(const Ray& ray, double t_min, double t_max) {
  RTCRay r{};
  r.org_x = static_cast<float>(ray.origin.x());
  r.org_y = static_cast<float>(ray.origin.y());
  r.org_z = static_cast<float>(ray.origin.z());
  r.dir_x = static_cast<float>(ray.direction.x());
  r.dir_y = static_cast<float>(ray.direction.y());
  r.dir_z = static_cast<float>(ray.direction.z());
  r.tnear = static_cast<float>(t_min);
  r.tfar =
      std::isfinite(t_max) ? static_cast<float>(t_max) : std::numeric_limits<float>::infinity();
  r.mask = ~0u;
  r.time = 0;
  r.flags = 0;
  return r;
}

}  // namespace

std::optional<Hit> RayCaster::closest_hit(const Ray& ray, double t_min, double t_max) const {
  RTCRayHit rh{};
  rh.ray = to_embree(ray, t_min, t_max);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(impl_->rtc_scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

  Hit hit;
  hit.polygon = impl_->triangle_polygon[rh.hit.primID];
  const Polygon& polygon = scene_.polygons[hit.polygon];
  hit.normal = polygon.normal;
  const double cos_in = polygon.normal.dot(ray.direction);
  hit.front_facing = cos_in < 0;
  // Recompute the distance in double against the polygon's plane; Embree's float t is only
  // ~1e-7 relative. Keep Embree's value when the ray grazes the plane.
  double t = rh.ray.tfar;
  if (std::abs(cos_in) > relative::kMatch) {
    const double t_plane = polygon.normal.dot(polygon.vertices.front() - ray.origin) / cos_in;
    if (std::isfinite(t_plane) && std::abs(t_plane - t) <= 1e-3 * std::max(1.0, std::abs(t))) {
      t = t_plane;
    }
  }
  hit.distance = t;
  hit.point = ray.origin + t * ray.direction;
  hit.direction = ray.direction;
  return hit;
}

bool RayCaster::occluded(const Ray& ray, double t_min, double t_max) const {
  RTCRay r = to_embree(ray, t_min, t_max);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded1(impl_->rtc_scene, &context, &r);
  return r.tfar < 0;  // Embree sets tfar to -inf on a hit
}

void RayCaster::occluded(const std::vector<Segment>& segments, std::vector<char>& blocked) const {
  thread_local std::vector<RTCRay> rays;
  rays.resize(segments.size());
  for (size_t i = 0; i < segments.size(); ++i)
    rays[i] = to_embree(segments[i].ray, segments[i].t_min, segments[i].t_max);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcOccluded1M(impl_->rtc_scene, &context, rays.data(), static_cast<unsigned>(rays.size()),
                sizeof(RTCRay));
  blocked.resize(segments.size());
  for (size_t i = 0; i < segments.size(); ++i) blocked[i] = rays[i].tfar < 0;
}

Rgb RayCaster::transmittance(const Ray& ray, double t_min, double t_max, double gap) const {
  if (!has_filters_) return occluded(ray, t_min, t_max) ? Rgb::Zero() : Rgb::Ones();
  Rgb passed = Rgb::Ones();
  for (double t = t_min;;) {
    const auto hit = closest_hit(ray, t, t_max);
    if (!hit) return passed;
    passed =
        passed.cwiseProduct(scene_.materials[scene_.polygons[hit->polygon].material].transmittance);
    if (passed == Rgb::Zero()) return passed;
    // On past it, and never back: the distance recomputed in double can fall short of the
    // float one Embree found at or beyond t.
    t = std::max(hit->distance, t) + gap;
  }
}

namespace {

/// A path of RayCaster::follow on its way: a ray and what it carries.
struct Branch {
  Ray ray;
  Rgb weight;
  double t_min;
  RayCaster::Bends bends;
  Rgb attenuation = Rgb::Zero();  ///< Of the medium this leg runs through (0: outside)
  bool first_leg() const { return bends.reflections == 0 && bends.refractions == 0; }
};

/// The branches of `b` at a refracting interface it meets at `hit` (000 §4; fronts face out,
/// so a front is crossed into the medium, a back out of it): the refracted ray per distinct
/// index (one ray, or one per channel when dispersive), times what the crossing passes and
/// 1 / eta^2; and, when interfaces reflect, the reflected ray with the Fresnel reflection and
/// the channels past the critical angle.
void split_at_interface(const Branch& b, const Hit& hit, const Refraction& r, bool reflects,
                        double gap, std::vector<Branch>& branches) {
  const Vec3& d = b.ray.direction;
  const double cos_near = std::abs(hit.normal.dot(d));
  RayCaster::Bends next = b.bends;
  ++next.refractions;
  const Rgb beyond = hit.front_facing ? r.attenuation : Rgb::Zero();
  Rgb reflected = Rgb::Zero();
  const int rays = r.dispersive() ? 3 : 1;
  for (int c = 0; c < rays; ++c) {
    const Rgb channels = r.dispersive() ? Rgb(Rgb::Unit(c)) : Rgb(Rgb::Ones());
    const double eta = hit.front_facing ? r.ior[c] : 1 / r.ior[c];
    const std::optional<Vec3> t = refract(d, hit.normal, eta);
    if (!t) {
      reflected += channels;  // total internal reflection, Fresnel or not
      continue;
    }
    Rgb passed = channels.cwiseProduct(r.transmittance);
    if (r.fresnel) {
      const double fresnel = fresnel_transmission(cos_near, eta);
      passed = fresnel * channels;
      reflected += (1 - fresnel) * channels;
    }
    branches.push_back(
        {{hit.point, *t}, b.weight.cwiseProduct(passed) / (eta * eta), gap, next, beyond});
  }
  if (reflected != Rgb::Zero() && reflects) {
    // Back into the medium the ray came through.
    const Rgb same_side = hit.front_facing ? Rgb(Rgb::Zero()) : r.attenuation;
    branches.push_back({{hit.point, reflect(d, hit.normal)},
                        b.weight.cwiseProduct(reflected),
                        gap,
                        next,
                        same_side});
  }
}

}  // namespace

void RayCaster::follow(const Ray& ray, Bends limits, double gap,
                       const std::function<void(const Hit&, const Rgb&, int)>& visit,
                       double near) const {
  std::vector<Branch> branches{{ray, Rgb::Ones(), 0.0, {}}};
  while (!branches.empty()) {
    Branch b = branches.back();
    branches.pop_back();
    double attenuated_to = 0;  // distance along this leg the medium has dimmed the weight to
    while (true) {
      const auto hit = closest_hit(b.ray, b.t_min);
      if (!hit) break;
      if (b.first_leg() && hit->distance < near) {
        b.t_min = std::max(hit->distance, b.t_min) + gap;
        continue;
      }
      if (b.attenuation != Rgb::Zero() && hit->distance > attenuated_to) {
        const Rgb lost = -b.attenuation * (hit->distance - attenuated_to);
        b.weight = b.weight.cwiseProduct(Rgb(lost.array().exp()));
        attenuated_to = hit->distance;
      }
      visit(*hit, b.weight, b.bends.reflections + b.bends.refractions);
      const Material& m = scene_.materials[scene_.polygons[hit->polygon].material];
      if (hit->front_facing && m.is_mirror() && b.bends.reflections < limits.reflections &&
          (limits.glossy_as_mirror || !m.is_glossy_mirror())) {
        Bends next = b.bends;
        ++next.reflections;
        branches.push_back({{hit->point, reflect(b.ray.direction, hit->normal)},
                            b.weight.cwiseProduct(m.specular),
                            gap,
                            next,
                            b.attenuation});
      }
      if (m.refracts() && b.bends.refractions < limits.refractions)
        split_at_interface(b, *hit, *m.refraction, limits.interface_reflections, gap, branches);
      const Rgb passed =
          limits.glossy_as_mirror ? Rgb(m.transmittance + m.glossy_transmittance) : m.transmittance;
      b.weight = b.weight.cwiseProduct(passed);
      if (b.weight == Rgb::Zero()) break;
      b.t_min = std::max(hit->distance, b.t_min) + gap;  // on past it, never back
    }
  }
}

}  // namespace rad
