// `radiosity info SCENE`: what a scene holds, without computing anything.
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/commands.h"
#include "cli/common.h"
#include "scene/scene_loader.h"

namespace rad::cli {
namespace {

struct InfoOptions {
  std::string scene;
  bool json = false;
};

std::string triple(const Vec3& v) {
  std::ostringstream out;
  out << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return out.str();
}

nlohmann::json to_json(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

void run_info(const InfoOptions& options) {
  const Scene scene = load_scene_reporting(options.scene);

  std::vector<int> polygons_per_material(scene.materials.size(), 0);
  std::vector<double> area_per_material(scene.materials.size(), 0.0);
  for (const Polygon& p : scene.polygons) {
    ++polygons_per_material[p.material];
    area_per_material[p.material] += p.area;
  }
  const Bounds bounds = scene.bounds();

  if (options.json) {
    nlohmann::json out;
    out["scene"] = options.scene;
    out["objects"] = scene.objects.size();
    out["polygons"] = scene.polygons.size();
    out["vertices"] = scene.vertex_count();
    out["total_area"] = scene.total_area();
    out["bounds"] = {{"min", to_json(bounds.lo)}, {"max", to_json(bounds.hi)}};
    out["emitters"] = scene.emitter_count();
    out["emitted_power"] = to_json(scene.emitted_power());
    out["lights"] = nlohmann::json::array();
    for (const PointLight& light : scene.lights) {
      out["lights"].push_back(
          {{"position", to_json(light.position)}, {"intensity", to_json(light.intensity)}});
    }
    out["light_power"] = to_json(scene.light_power());
    out["warnings"] = scene.warnings;
    for (size_t m = 0; m < scene.materials.size(); ++m) {
      const Material& mat = scene.materials[m];
      out["materials"].push_back({{"name", mat.name},
                                  {"reflectance", to_json(mat.reflectance)},
                                  {"emission", to_json(mat.emission)},
                                  {"transmittance", to_json(mat.transmittance)},
                                  {"specular", to_json(mat.specular)},
                                  {"gloss", mat.gloss},
                                  {"glossy_transmittance", to_json(mat.glossy_transmittance)},
                                  {"polygons", polygons_per_material[m]},
                                  {"area", area_per_material[m]}});
      if (mat.refracts()) {
        const Refraction& r = *mat.refraction;
        out["materials"].back()["refraction"] = {{"ior", to_json(r.ior)},
                                                 {"transmittance", to_json(r.transmittance)},
                                                 {"fresnel", r.fresnel},
                                                 {"attenuation", to_json(r.attenuation)}};
      }
    }
    if (scene.camera) {
      const CameraSpec& c = *scene.camera;
      out["camera"] = {{"eye", to_json(c.eye)}, {"look_at", to_json(c.look_at)},
                       {"up", to_json(c.up)},   {"fov_deg", c.fov_deg},
                       {"width", c.width},      {"height", c.height}};
    }
    std::cout << out.dump(2) << "\n";
    return;
  }

  std::cout << std::setprecision(6);
  std::cout << "scene          " << options.scene << "\n"
            << "objects        " << scene.objects.size() << "\n"
            << "polygons       " << scene.polygons.size() << "\n"
            << "vertices       " << scene.vertex_count() << " (polygon corners)\n"
            << "total area     " << scene.total_area() << "\n"
            << "bounds         " << triple(bounds.lo) << " to " << triple(bounds.hi)
            << ", diagonal " << bounds.diagonal() << "\n"
            << "emitters       " << scene.emitter_count() << " polygon"
            << (scene.emitter_count() == 1 ? "" : "s") << "\n"
            << "emitted power  " << triple(scene.emitted_power())
            << " RGB (exitance x area; W when lengths are metres)\n";
  if (!scene.lights.empty()) {
    std::cout << "point lights   " << scene.lights.size() << ", power "
              << triple(scene.light_power()) << " RGB (4 pi x intensity)\n";
  }
  if (scene.camera) {
    const CameraSpec& c = *scene.camera;
    std::cout << "camera         eye " << triple(c.eye) << ", look_at " << triple(c.look_at)
              << ", fov " << c.fov_deg << " deg, " << c.width << " x " << c.height << "\n";
  } else {
    std::cout << "camera         none\n";
  }
  std::cout << "materials      " << scene.materials.size() << "\n";
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    const Material& mat = scene.materials[m];
    // A name is the file's: its escape sequences must not reach the terminal.
    std::string name = mat.name;
    std::replace_if(name.begin(), name.end(), is_control_byte, '?');
    std::cout << "  " << std::left << std::setw(12) << name << std::right << " reflectance "
              << triple(mat.reflectance) << "  emission " << triple(mat.emission) << "  ";
    // The paper-000 keys only where they are set, so opaque scenes read as before.
    if (mat.is_filter()) std::cout << "transmittance " << triple(mat.transmittance) << "  ";
    if (mat.is_mirror()) std::cout << "specular " << triple(mat.specular) << "  ";
    if (mat.is_glossy_pane())
      std::cout << "glossy transmittance " << triple(mat.glossy_transmittance) << "  ";
    if (mat.is_glossy()) std::cout << "gloss " << mat.gloss << " rad  ";
    if (mat.refracts()) {
      const Refraction& r = *mat.refraction;
      std::cout << "ior " << triple(r.ior) << "  "
                << (r.fresnel ? std::string("fresnel") : "transmittance " + triple(r.transmittance))
                << "  ";
      if ((r.attenuation.array() > 0).any())
        std::cout << "attenuation " << triple(r.attenuation) << "  ";
    }
    std::cout << polygons_per_material[m]
              << (polygons_per_material[m] == 1 ? " polygon" : " polygons") << ", area "
              << area_per_material[m] << "\n";
  }
  std::cout << "warnings       " << scene.warnings.size()
            << (scene.warnings.empty() ? "" : " (on stderr)") << "\n";
}

}  // namespace

void add_info_command(CLI::App& app, Run& run) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* sub = app.add_subcommand(
      "info", "Load and validate a scene; print counts, bounds, materials, emitters, warnings.");
  sub->footer(
      "Prints objects, polygons, vertices, total area, bounding box, emitters and emitted power\n"
      "(exitance x area: W when lengths are metres), the camera, and the materials with the "
      "polygon\n"
      "count and area of each. Warnings (what loading fixed: repeated vertices merged, slightly\n"
      "non-planar polygons split into triangles) go to stderr. --json prints the same as JSON.");
  sub->add_option("scene", options->scene, kSceneHelp)->required();
  sub->add_flag("--json", options->json, "Print the summary as JSON");
  sub->callback([options, &run] { run = [options] { run_info(*options); }; });
}

}  // namespace rad::cli
