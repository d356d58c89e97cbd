#include "scene/scene_loader.h"

#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <sstream>
#include <tuple>

#include "scene/closed_surface.h"
#include "scene/error.h"
#include "scene/input_files.h"
#include "scene/limits.h"
#include "scene/mesh_object.h"
#include "scene/mesh_reader.h"
#include "scene/polygon_validation.h"
#include "scene/scene_checks.h"
#include "scene/scene_json.h"

namespace rad {
namespace {

using scene_json::Json;
using scene_json::parse_json;
using scene_json::Reader;

/// The refraction keys of a material with "ior" (000 §4); transmittance 1 when omitted.
Refraction read_refraction(const Reader& in, const std::string& where, const Json& j) {
  Refraction r;
  r.ior = in.rgb(j["ior"], where + ".ior");
  for (int c = 0; c < 3; ++c) {
    if (!(r.ior[c] >= 1)) {
      std::ostringstream msg;
      msg << "ior[" << c << "] = " << r.ior[c]
          << " is below 1 (the index of the medium behind the front side, the outside being 1;"
             " face the polygons out of the denser medium)";
      in.fail(where, msg.str());
    }
  }
  if (j.contains("fresnel")) {
    if (!j["fresnel"].is_boolean()) in.fail(where + ".fresnel", "expected true or false");
    r.fresnel = j["fresnel"].get<bool>();
  }
  if (j.contains("transmittance")) {
    if (r.fresnel) {
      in.fail(where,
              "has both \"transmittance\" and \"fresnel\": true (the Fresnel "
              "transmission replaces the transmittance; give one)");
    }
    r.transmittance = in.rgb(j["transmittance"], where + ".transmittance");
  }
  if (j.contains("attenuation")) r.attenuation = in.rgb(j["attenuation"], where + ".attenuation");
  for (int c = 0; c < 3; ++c) {
    if (!(r.attenuation[c] >= 0)) {
      std::ostringstream msg;
      msg << "attenuation[" << c << "] = " << r.attenuation[c]
          << " is negative (a medium cannot add light along a path)";
      in.fail(where, msg.str());
    }
  }
  return r;
}

Material read_material(const Reader& in, const std::string& name, const Json& j) {
  const std::string where = "materials.\"" + name + "\"";
  in.require_object(j, where,
                    {"reflectance", "emission", "transmittance", "specular", "gloss", "ior",
                     "fresnel", "attenuation"});
  Material m;
  m.name = name;
  // A refracting material is clear glass unless told otherwise: no diffuse part by default.
  if (j.contains("ior")) m.reflectance = Rgb::Zero();
  if (j.contains("reflectance")) m.reflectance = in.rgb(j["reflectance"], where + ".reflectance");
  if (j.contains("emission")) m.emission = in.rgb(j["emission"], where + ".emission");
  if (j.contains("ior")) {
    m.refraction = read_refraction(in, where, j);
  } else {
    for (const char* key : {"fresnel", "attenuation"}) {
      if (j.contains(key))
        in.fail(where, std::string("has \"") + key + "\" but no \"ior\" (it refracts nothing)");
    }
    if (j.contains("transmittance"))
      m.transmittance = in.rgb(j["transmittance"], where + ".transmittance");
  }
  if (j.contains("specular")) m.specular = in.rgb(j["specular"], where + ".specular");
  if (j.contains("gloss")) {
    m.gloss = in.number(j["gloss"], where + ".gloss");
    if (!(m.gloss >= 0 && m.gloss <= std::numbers::pi)) {
      std::ostringstream msg;
      msg << "gloss = " << m.gloss << " is outside [0, pi] (the lobe's spread in radians)";
      in.fail(where + ".gloss", msg.str());
    }
    if (m.gloss > 0 && j.contains("ior"))
      in.fail(where, "has \"gloss\" with \"ior\": rough refracting interfaces are not supported");
    if (m.gloss > 0 && m.is_filter()) {  // a roughened pane: its transmission goes into the lobe
      m.glossy_transmittance = m.transmittance;
      m.transmittance = Rgb::Zero();
    }
    if (m.gloss > 0 && !m.is_glossy())
      in.fail(where, "has \"gloss\" but no \"specular\" or \"transmittance\" (a lobe of nothing)");
  }
  // What a refracting interface passes counts against the same incident light as a filter's;
  // the Fresnel transmission is largest at normal incidence, 1 - ((n - 1) / (n + 1))^2.
  Rgb passed = m.transmittance + m.glossy_transmittance;
  if (m.refracts()) {
    const Refraction& r = *m.refraction;
    passed = r.transmittance;
    if (r.fresnel) {
      const Rgb reflected = ((r.ior.array() - 1) / (r.ior.array() + 1)).square();
      passed = Rgb::Ones() - reflected;
    }
  }
  for (int c = 0; c < 3; ++c) {
    if (!(m.reflectance[c] >= 0 && m.reflectance[c] < 1)) {
      std::ostringstream msg;
      msg << "reflectance[" << c << "] = " << m.reflectance[c]
          << " is outside [0, 1) (a surface cannot reflect more than it receives)";
      in.fail(where, msg.str());
    }
    if (m.emission[c] < 0) {
      std::ostringstream msg;
      msg << "emission[" << c << "] = " << m.emission[c] << " is negative";
      in.fail(where, msg.str());
    }
    for (const auto& [key, value] : {std::pair<const char*, double>{"transmittance", passed[c]},
                                     {"specular", m.specular[c]}}) {
      if (!(value >= 0 && value <= 1)) {
        std::ostringstream msg;
        msg << key << "[" << c << "] = " << value << " is outside [0, 1]";
        in.fail(where, msg.str());
      }
    }
    // What a filter passes and a mirror reflects come out of the same incident light as the
    // diffuse part (000 §2.2, §3).
    const double sum = m.reflectance[c] + passed[c] + m.specular[c];
    if (sum > 1) {
      std::ostringstream msg;
      msg << "reflectance + transmittance + specular = " << sum << " in channel " << c
          << " exceeds 1 (a surface cannot send on more than it receives"
          << (j.contains("reflectance") ? ")" : "; reflectance is 0.5 when omitted)");
      in.fail(where, msg.str());
    }
  }
  return m;
}

/// Vertex normals for a smooth mesh object: at each vertex position, the area-weighted mean of
/// the normals of the object's polygons that have a vertex there (positions match exactly, as
/// the mesh's shared vertices do). A vertex whose normals cancel keeps its polygon's normal.
void smooth_normals(std::vector<Polygon>& polygons, int first, int count) {
  std::map<std::array<double, 3>, Vec3> sum;
  const auto key = [](const Vec3& v) { return std::array<double, 3>{v.x(), v.y(), v.z()}; };
  for (int i = first; i < first + count; ++i) {
    for (const Vec3& v : polygons[i].vertices) {
      auto [it, added] = sum.try_emplace(key(v), Vec3::Zero());
      it->second += polygons[i].area * polygons[i].normal;
    }
  }
  for (int i = first; i < first + count; ++i) {
    Polygon& p = polygons[i];
    p.vertex_normals.clear();
    for (const Vec3& v : p.vertices) {
      const Vec3& s = sum[key(v)];
      p.vertex_normals.push_back(s.norm() > 0 ? Vec3(s.normalized()) : p.normal);
    }
  }
}

/// "lights": a list of isotropic point lights, {"position": [x, y, z], "intensity": [r, g, b]}.
/// A light inside a closed object is allowed (it lights nothing outside it).
std::vector<PointLight> read_lights(const Reader& in, const Json& j) {
  if (!j.is_array()) in.fail("lights", "expected a list of point lights");
  if (static_cast<long long>(j.size()) > limits::kPolygons)
    in.fail("lights", "more than " + std::to_string(limits::kPolygons) + " lights");
  std::vector<PointLight> lights;
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string where = "lights[" + std::to_string(i) + "]";
    in.require_object(j[i], where, {"position", "intensity"});
    for (const char* key : {"position", "intensity"}) {
      if (!j[i].contains(key)) in.fail(where, std::string("missing \"") + key + "\"");
    }
    PointLight light;
    light.position = in.vec3(j[i]["position"], where + ".position");
    light.intensity = in.rgb(j[i]["intensity"], where + ".intensity");
    for (int c = 0; c < 3; ++c) {
      if (light.intensity[c] < 0) {
        std::ostringstream msg;
        msg << "intensity[" << c << "] = " << light.intensity[c] << " is negative";
        in.fail(where, msg.str());
      }
    }
    lights.push_back(light);
  }
  return lights;
}

CameraSpec read_camera(const Reader& in, const Json& j) {
  in.require_object(j, "camera", {"eye", "look_at", "up", "fov_deg", "width", "height"});
  CameraSpec spec;
  for (const char* key : {"eye", "look_at", "fov_deg"}) {
    if (!j.contains(key)) in.fail("camera", std::string("missing \"") + key + "\"");
  }
  spec.eye = in.vec3(j["eye"], "camera.eye");
  spec.look_at = in.vec3(j["look_at"], "camera.look_at");
  if (j.contains("up")) spec.up = in.vec3(j["up"], "camera.up");
  spec.fov_deg = in.number(j["fov_deg"], "camera.fov_deg");
  if (j.contains("width")) spec.width = in.positive_int(j["width"], "camera.width");
  if (j.contains("height")) spec.height = in.positive_int(j["height"], "camera.height");
  for (const auto& [side, name] : {std::pair{spec.width, "width"}, {spec.height, "height"}}) {
    if (side > limits::kImageSide) {
      in.fail(std::string("camera.") + name,
              std::to_string(side) + " pixels, more than the limit of " +
                  std::to_string(limits::kImageSide) + " (as --width and --height)");
    }
  }
  try {
    Camera check(spec);  // same validation as at render time, reported with the file name
  } catch (const InputError& e) {
    throw InputError(in.at(e.what()));
  }
  return spec;
}

/// "mirror_depth" and "refraction_depth", each an integer from 0 to 8.
void read_depths(const Reader& in, const Json& root, Scene& scene) {
  for (const auto& [key, depth, what] :
       {std::tuple{"mirror_depth", &scene.mirror_depth, "reflections followed"},
        {"refraction_depth", &scene.refraction_depth, "refracting interfaces crossed"}}) {
    if (!root.contains(key)) continue;
    const Json& value = root[key];
    if (!value.is_number_integer() || value.get<long long>() < 0 || value.get<long long>() > 8) {
      in.fail(key,
              std::string("expected an integer from 0 to 8 (") + what + "), got " + value.dump());
    }
    *depth = value.get<int>();
  }
}

/// The named materials into scene.materials; returns each name's index.
std::map<std::string, int> read_materials(const Reader& in, const Json& root, Scene& scene) {
  std::map<std::string, int> material_index;
  if (!root.contains("materials")) return material_index;
  const Json& materials = root["materials"];
  if (!materials.is_object()) in.fail("materials", "expected an object of named materials");
  for (const auto& [name, value] : materials.items()) {
    material_index[name] = static_cast<int>(scene.materials.size());
    scene.materials.push_back(read_material(in, name, value));
  }
  return material_index;
}

/// An object's inline "polygons": lists of [x, y, z] vertices, at most the vertex limit each.
std::vector<std::vector<Vec3>> read_inline_polygons(const Reader& in, const Json& polygons,
                                                    const std::string& where) {
  if (!polygons.is_array()) in.fail(where + ".polygons", "expected a list of polygons");
  std::vector<std::vector<Vec3>> faces;
  for (size_t p = 0; p < polygons.size(); ++p) {
    const std::string pw = where + " polygon " + std::to_string(p);
    if (!polygons[p].is_array()) in.fail(pw, "expected a list of [x, y, z] vertices");
    if (polygons[p].size() > static_cast<size_t>(limits::kPolygonVertices)) {
      in.fail(pw, "has " + std::to_string(polygons[p].size()) + " vertices, more than " +
                      std::to_string(limits::kPolygonVertices));
    }
    std::vector<Vec3> vertices;
    for (size_t v = 0; v < polygons[p].size(); ++v) {
      vertices.push_back(in.vec3(polygons[p][v], pw + " vertex " + std::to_string(v)));
    }
    faces.push_back(std::move(vertices));
  }
  return faces;
}

/// objects[i]: its polygons (inline or from a mesh file beside the scene file), validated, into
/// scene.polygons, and the object into scene.objects. An OBJ object without "material" takes
/// its faces' own (usemtl, from its mtllib libraries; mesh_object.h).
void read_object(const Reader& in, const Json& o, size_t i, const std::filesystem::path& folder,
                 const std::map<std::string, int>& material_index, const SceneOptions& options,
                 LibraryMaterials& library_materials, Scene& scene, InputFiles* files) {
  std::string where = "objects[" + std::to_string(i) + "]";
  in.require_object(o, where, {"name", "mesh", "polygons", "material", "smooth"});
  SceneObject object;
  if (o.contains("name")) {
    object.name = in.string(o["name"], where + ".name");
    where += " \"" + object.name + "\"";
  }
  if (o.contains("mesh") == o.contains("polygons")) {
    in.fail(where, "needs exactly one of \"mesh\" or \"polygons\"");
  }
  if (o.contains("mesh")) object.mesh = in.string(o["mesh"], where + ".mesh");
  const bool own_materials = !o.contains("material") && names_own_materials(object.mesh);
  if (!o.contains("material") && !own_materials) {
    in.fail(where, o.contains("mesh") ? "missing \"material\" (only an OBJ mesh names its own)"
                                      : "missing \"material\"");
  }
  if (!own_materials) {
    const std::string material = in.string(o["material"], where + ".material");
    const auto found = material_index.find(material);
    if (found == material_index.end()) {
      in.fail(where, "unknown material \"" + material + "\"");
    }
    object.material = found->second;
  }
  object.first_polygon = static_cast<int>(scene.polygons.size());
  const int object_id = static_cast<int>(i);

  std::vector<std::vector<Vec3>> faces;
  std::vector<int> face_material;
  if (o.contains("mesh")) {
    where += " (" + object.mesh + ")";
    MeshMaterials use;
    faces = read_mesh_faces(folder / object.mesh, in.at(where), scene.warnings, files, &use);
    if (own_materials) {
      face_material = obj_face_materials(use, folder / object.mesh, in.at(where), material_index,
                                         scene, library_materials, files);
      object.material = common_material(face_material);
    }
  } else {
    faces = read_inline_polygons(in, o["polygons"], where);
  }
  if (!own_materials) face_material.assign(faces.size(), object.material);
  add_object_faces(std::move(faces), face_material, in.at(where), o.contains("mesh"), object_id,
                   options.flip_normals, scene);
  object.polygon_count = static_cast<int>(scene.polygons.size()) - object.first_polygon;
  if (o.contains("smooth")) {
    if (!o["smooth"].is_boolean()) in.fail(where + ".smooth", "expected true or false");
    if (o["smooth"].get<bool>()) {
      if (!o.contains("mesh"))
        in.fail(where, "\"smooth\" needs a \"mesh\" (its faces share vertices)");
      smooth_normals(scene.polygons, object.first_polygon, object.polygon_count);
    }
  }
  check_refracting_closure(in.at(where), object, scene);
  scene.objects.push_back(std::move(object));
}

}  // namespace

Scene parse_scene(const std::string& json_text, const std::filesystem::path& file,
                  InputFiles* files, const SceneOptions& options) {
  const Reader in(file.string());
  const Json root = parse_json(json_text, file);
  Scene scene;
  scene.path = file;
  in.require_object(
      root, "top level",
      {"materials", "objects", "lights", "camera", "mirror_depth", "refraction_depth"});
  read_depths(in, root, scene);
  const std::map<std::string, int> material_index = read_materials(in, root, scene);
  LibraryMaterials library_materials;
  if (!root.contains("objects")) in.fail("top level", "missing \"objects\"");
  const Json& objects = root["objects"];
  if (!objects.is_array()) in.fail("objects", "expected a list of objects");
  for (size_t i = 0; i < objects.size(); ++i)
    read_object(in, objects[i], i, file.parent_path(), material_index, options, library_materials,
                scene, files);
  if (scene.polygons.empty()) in.fail("objects", "the scene has no polygons");
  if (root.contains("lights")) scene.lights = read_lights(in, root["lights"]);
  if (root.contains("camera")) scene.camera = read_camera(in, root["camera"]);
  check_power(scene, file.string());
  check_facing(scene);
  return scene;
}

Scene load_scene(const std::filesystem::path& file, InputFiles* files,
                 const SceneOptions& options) {
  if (is_supported_mesh_extension(file)) {  // a bare mesh: `radiosity info room.obj`
    Scene scene = mesh_scene(file, files, options.flip_normals);
    check_power(scene, file.string());
    check_facing(scene);
    return scene;
  }
  if (const std::string* recorded = files ? files->find(file) : nullptr)
    return parse_scene(*recorded, file, files, options);
  check_input_file(file, "scene file");
  std::ifstream stream(file, std::ios::binary);
  if (!stream) throw InputError(file.string() + ": cannot open scene file");
  std::error_code error;
  const std::uintmax_t bytes = std::filesystem::file_size(file, error);
  if (!error && bytes > limits::kSceneFileBytes) {
    throw InputError(file.string() + ": scene file of " + std::to_string(bytes >> 20) +
                     " MiB, more than the limit of " +
                     std::to_string(limits::kSceneFileBytes >> 20) + " MiB");
  }
  std::ostringstream text;
  text << stream.rdbuf();
  if (stream.bad()) throw InputError(file.string() + ": cannot read scene file");
  if (files) files->add(file, text.str());
  return parse_scene(text.str(), file, files, options);
}

}  // namespace rad
