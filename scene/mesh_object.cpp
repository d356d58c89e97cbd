#include "scene/mesh_object.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "scene/error.h"
#include "scene/limits.h"
#include "scene/mesh_formats.h"
#include "scene/mtl.h"
#include "scene/polygon_validation.h"
#include "scene/ray_caster.h"
#include "scene/scene_checks.h"

namespace rad {
namespace {

/// The grey a face takes when its material is unknown: the JSON scene's default reflectance.
int grey_material(Scene& scene, LibraryMaterials& added) {
  if (added.grey < 0) {
    added.grey = static_cast<int>(scene.materials.size());
    Material grey;
    grey.name = "grey (no material)";
    scene.materials.push_back(grey);
  }
  return added.grey;
}

std::string faces_text(long long n) { return std::to_string(n) + (n == 1 ? " face" : " faces"); }
std::string faces_are(long long n) { return faces_text(n) + (n == 1 ? " is" : " are"); }

}  // namespace

std::vector<int> obj_face_materials(const MeshMaterials& use, const std::filesystem::path& mesh,
                                    const std::string& where,
                                    const std::map<std::string, int>& named, Scene& scene,
                                    LibraryMaterials& added, InputFiles* files) {
  // The scene file's materials first; then every library's, added to the scene once per
  // library and name (a name two libraries hold is the first one's, as the OBJ lists them).
  std::map<std::string, int, std::less<>> by_name(named.begin(), named.end());
  std::string libraries;
  for (size_t l = 0; l < use.libraries.size(); ++l) {
    const std::filesystem::path path = mesh.parent_path() / use.libraries[l];
    libraries += (libraries.empty() ? "" : ", ") + use.libraries[l];
    std::string text;
    try {
      text = mesh_formats::read_model_file(path, "material library", where, files);
    } catch (const InputError& e) {  // missing or unreadable: its faces go grey, said below
      scene.warnings.push_back(std::string(e.what()) + " (mtllib at line " +
                               std::to_string(use.library_line[l]) + ")");
      continue;
    }
    for (auto& [name, material] : parse_material_library(text, path.string(), scene.warnings)) {
      const auto [it, fresh] =
          added.index.try_emplace({path.string(), name}, static_cast<int>(scene.materials.size()));
      if (fresh) scene.materials.push_back(material);
      by_name.try_emplace(name, it->second);
    }
  }

  std::vector<long long> faces_of(use.names.size(), 0);
  long long unnamed = 0;
  for (const int name : use.face_name) (name < 0 ? unnamed : faces_of[name]) += 1;
  std::vector<int> material_of(use.names.size());
  for (size_t n = 0; n < use.names.size(); ++n) {
    const auto found = by_name.find(use.names[n]);
    if (found != by_name.end()) {
      material_of[n] = found->second;
      continue;
    }
    if (faces_of[n] == 0) continue;  // a usemtl no face follows
    material_of[n] = grey_material(scene, added);
    scene.warnings.push_back(
        where + ": line " + std::to_string(use.first_line[n]) + ": material '" + use.names[n] +
        "' is in " + (libraries.empty() ? "no library (no mtllib)" : "none of " + libraries) +
        ": its " + faces_are(faces_of[n]) + " grey (reflectance 0.5)");
  }
  if (unnamed > 0) {
    scene.warnings.push_back(
        where + ": " + faces_text(unnamed) +
        (use.names.empty() ? " and no material (usemtl)" : " before the first usemtl") +
        ": grey (reflectance 0.5), emitting nothing");
  }
  std::vector<int> face_material;
  face_material.reserve(use.face_name.size());
  for (const int name : use.face_name)
    face_material.push_back(name < 0 ? grey_material(scene, added) : material_of[name]);
  return face_material;
}

int common_material(const std::vector<int>& face_material) {
  const bool one =
      !face_material.empty() && std::all_of(face_material.begin(), face_material.end(),
                                            [&](int m) { return m == face_material.front(); });
  return one ? face_material.front() : -1;
}

void add_object_faces(std::vector<std::vector<Vec3>> faces, const std::vector<int>& face_material,
                      const std::string& where, bool from_mesh, int object, bool flip,
                      Scene& scene) {
  const std::string element = from_mesh ? " face " : " polygon ";
  long long dropped = 0;
  size_t first_dropped = 0;
  for (size_t f = 0; f < faces.size(); ++f) {
    if (from_mesh && holds_no_area(faces[f])) {  // exported meshes hold slivers and collapsed faces
      if (dropped++ == 0) first_dropped = f;
      continue;
    }
    if (flip) std::reverse(faces[f].begin(), faces[f].end());
    const int index = static_cast<int>(f);
    for (Polygon& p : make_polygons(std::move(faces[f]), where + element + std::to_string(f),
                                    face_material[f], object, index, scene.warnings)) {
      scene.polygons.push_back(std::move(p));
    }
    if (static_cast<long long>(scene.polygons.size()) > limits::kPolygons) {
      throw InputError(where + ": the scene has more than " + std::to_string(limits::kPolygons) +
                       " polygons");
    }
  }
  if (dropped > 0) {
    scene.warnings.push_back(where + ": left out " + faces_text(dropped) +
                             " of no area (fewer than 3 distinct vertices, or collinear), from" +
                             element + std::to_string(first_dropped) + " on: they carry no light");
  }
}

CameraSpec camera_from_bounds(const Scene& scene) {
  const Bounds bounds = scene.bounds();
  const Vec3 middle = (bounds.lo + bounds.hi) / 2;
  const RayCaster caster(scene);
  const double skip = scene.tolerance().pad;  // a polygon through the middle is no wall
  int walls = 0;                              // fronts met from the middle
  double front_wall = 0;
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {-1.0, 1.0}) {
      const Vec3 direction = sign * Vec3::Unit(axis);
      const auto hit = caster.closest_hit({middle, direction}, skip);
      if (!hit || !hit->front_facing) continue;
      ++walls;
      if (axis == 2 && sign > 0) front_wall = hit->distance;
    }
  }
  CameraSpec spec;
  spec.look_at = middle;
  spec.up = Vec3::UnitY();
  if (walls == 6) {  // a room: stand just inside the +z wall
    spec.fov_deg = 60;
    spec.eye = middle + 0.9 * front_wall * Vec3::UnitZ();
  } else {  // an object: the sphere about its bounds fills the view
    spec.fov_deg = 40;
    const double distance =
        bounds.diagonal() / 2 / std::sin(spec.fov_deg / 2 * std::numbers::pi / 180);
    spec.eye = middle + 1.05 * distance * Vec3(0.5, 0.4, 1).normalized();
  }
  return spec;
}

Scene mesh_scene(const std::filesystem::path& file, InputFiles* files, bool flip) {
  Scene scene;
  scene.path = file;
  const std::string where = file.string();
  MeshMaterials use;
  std::vector<std::vector<Vec3>> faces = read_mesh_faces(file, where, scene.warnings, files, &use);
  use.face_name.resize(faces.size(), -1);  // the formats other than OBJ name no materials
  LibraryMaterials added;
  const std::vector<int> face_material =
      obj_face_materials(use, file, where, {}, scene, added, files);

  SceneObject object;
  object.name = file.stem().string();
  object.mesh = file.filename().string();
  object.material = common_material(face_material);
  add_object_faces(std::move(faces), face_material, where, true, 0, flip, scene);
  object.polygon_count = static_cast<int>(scene.polygons.size());
  scene.objects.push_back(object);
  check_refracting_closure(where, scene.objects.back(), scene);
  scene.camera = camera_from_bounds(scene);
  return scene;
}

}  // namespace rad
