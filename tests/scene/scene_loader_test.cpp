#include "scene/scene_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "scene/error.h"
#include "tests/bad_scene_cases.h"

namespace rad {
namespace {

const std::filesystem::path kData = RAD_TEST_DATA;
const std::filesystem::path kScenes = std::filesystem::path(RAD_SOURCE_DIR) / "data";

/// What loading fixed or noticed in a scene, less "nothing emits light": the scenes that test
/// reading have no light on purpose.
std::vector<std::string> fixes(const Scene& scene) {
  std::vector<std::string> out;
  for (const std::string& w : scene.warnings)
    if (w.find("nothing emits light") == std::string::npos) out.push_back(w);
  return out;
}

TEST(SceneLoader, LoadsCornellBox) {
  const Scene scene = load_scene(kScenes / "cornell-box/scene.json");
  // floor 1, ceiling 4 (around the light), light 1, back 1, right 1, left 2 (non-planar quad
  // split), two blocks of 5 faces each.
  EXPECT_EQ(scene.polygons.size(), 20u);
  EXPECT_EQ(scene.emitter_count(), 1);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("\"left wall\""), std::string::npos) << scene.warnings[0];
  // The light (130 x 105 mm) emits M = pi * (17, 12, 4).
  const Rgb power = scene.emitted_power();
  EXPECT_NEAR(power.x(), 130.0 * 105.0 * 53.4071, 1e-6 * power.x());
  ASSERT_TRUE(scene.camera);
  EXPECT_EQ(scene.camera->eye, Vec3(278, 273, -800));
  // 35 mm focal length, 25 mm film: fov = 2 atan(12.5 / 35).
  EXPECT_NEAR(scene.camera->fov_deg, 2 * std::atan(12.5 / 35) * 180 / std::numbers::pi, 1e-4);
  const Bounds b = scene.bounds();
  EXPECT_EQ(b.lo, Vec3(0, 0, 0));
  EXPECT_EQ(b.hi, Vec3(556, 548.8, 559.2));
  // Every polygon faces into the box: its normal points towards the box centre.
  const Vec3 centre(278, 274.4, 279.6);
  for (size_t i = 0; i < scene.polygons.size(); ++i) {
    const Polygon& p = scene.polygons[i];
    const bool block = scene.objects[p.object].name.find("block") != std::string::npos;
    if (block) continue;  // block faces point out of the blocks, not at the centre
    EXPECT_GT(p.normal.dot(centre - p.vertices[0]), 0)
        << scene.describe_polygon(static_cast<int>(i));
  }
}

TEST(SceneLoader, LoadsTheTestScenes) {
  const Scene cube = load_scene(kScenes / "closed-cube/scene.json");
  EXPECT_EQ(cube.polygons.size(), 6u);
  EXPECT_NEAR(cube.total_area(), 6.0, 1e-14);
  for (const Polygon& p : cube.polygons) {
    EXPECT_GT(p.normal.dot(Vec3(0.5, 0.5, 0.5) - p.vertices[0]), 0) << "cube faces point inward";
  }
  const Scene lof = load_scene(kScenes / "light-over-floor/scene.json");
  EXPECT_EQ(lof.polygons.size(), 3u);
  EXPECT_EQ(lof.emitter_count(), 1);
}

TEST(SceneLoader, ReadsEveryMeshFormat) {
  for (const char* name :
       {"square_obj.json", "square_off.json", "square_ply.json", "square_stl.json"}) {
    const Scene scene = load_scene(kData / "meshes" / name);
    EXPECT_NEAR(scene.total_area(), 1.0, 1e-12) << name;
    EXPECT_TRUE(fixes(scene).empty()) << name << ": " << fixes(scene).front();
    for (const Polygon& p : scene.polygons) {
      EXPECT_NEAR(p.normal.y(), 1.0, 1e-12) << name << ": counter-clockwise from +y is front";
    }
    EXPECT_EQ(scene.objects[0].mesh.empty(), false);
  }
  EXPECT_EQ(load_scene(kData / "meshes/square_stl.json").polygons.size(), 2u);
  EXPECT_EQ(load_scene(kData / "meshes/square_obj.json").polygons.size(), 1u);
}

TEST(SceneLoader, KeepsNonManifoldFaces) {
  // Three quads share one edge, which no half-edge mesh can hold; none of the user's polygons
  // may be lost.
  const Scene scene = load_scene(kData / "meshes/fin_obj.json");
  EXPECT_EQ(scene.polygons.size(), 3u);
  EXPECT_NEAR(scene.total_area(), 3.0, 1e-12);
  EXPECT_TRUE(fixes(scene).empty());
}

TEST(SceneLoader, DefaultsAndGreyShorthand) {
  const Scene scene = parse_scene(R"({"materials": {"m": {}, "g": {"reflectance": 0.25}},
      "objects": [{"material": "m", "polygons": [[[0,0,0],[1,0,0],[0,1,0]]]},
                  {"material": "g", "polygons": [[[0,0,1],[1,0,1],[0,1,1]]]}]})",
                                  "inline.json");
  EXPECT_EQ(scene.materials[scene.polygons[0].material].reflectance, Rgb(0.5, 0.5, 0.5));
  EXPECT_EQ(scene.materials[scene.polygons[0].material].emission, Rgb::Zero());
  EXPECT_EQ(scene.materials[scene.polygons[1].material].reflectance, Rgb(0.25, 0.25, 0.25));
  EXPECT_FALSE(scene.camera);
}

TEST(SceneLoader, ReadsFiltersAndMirrors) {
  // 000 §2.2, §3: transmittance and specular, RGB or one number, default 0; the three parts
  // may sum to exactly 1.
  const Scene scene = parse_scene(R"({"materials": {"m": {},
        "glass": {"reflectance": 0.1, "transmittance": [0.2, 0.5, 0.9], "emission": 1},
        "mirror": {"reflectance": [0.05, 0.1, 0], "specular": [0.95, 0.8, 1]}},
      "objects": [{"material": "m", "polygons": [[[0,0,0],[1,0,0],[0,1,0]]]},
                  {"material": "glass", "polygons": [[[0,0,1],[1,0,1],[0,1,1]]]},
                  {"material": "mirror", "polygons": [[[0,0,2],[1,0,2],[0,1,2]]]}]})",
                                  "inline.json");
  const auto material = [&](int p) { return scene.materials[scene.polygons[p].material]; };
  EXPECT_EQ(material(0).transmittance, Rgb::Zero());
  EXPECT_EQ(material(0).specular, Rgb::Zero());
  EXPECT_FALSE(material(0).is_filter() || material(0).is_mirror());
  EXPECT_EQ(material(1).transmittance, Rgb(0.2, 0.5, 0.9));
  EXPECT_TRUE(material(1).is_filter() && material(1).is_emitter());
  EXPECT_EQ(material(2).specular, Rgb(0.95, 0.8, 1));
  EXPECT_TRUE(material(2).is_mirror() && !material(2).is_filter());
}

// The six faces of the unit cube, fronts out (counter-clockwise seen from outside), as JSON;
// `faces` of them, and turned inside out when `inward`.
std::string cube_polygons(int faces = 6, bool inward = false) {
  const char* all[6] = {"[[0,0,0],[0,1,0],[1,1,0],[1,0,0]]", "[[0,0,1],[1,0,1],[1,1,1],[0,1,1]]",
                        "[[0,0,0],[1,0,0],[1,0,1],[0,0,1]]", "[[0,1,0],[0,1,1],[1,1,1],[1,1,0]]",
                        "[[0,0,0],[0,0,1],[0,1,1],[0,1,0]]", "[[1,0,0],[1,1,0],[1,1,1],[1,0,1]]"};
  std::string out = "[";
  for (int f = 0; f < faces; ++f) {
    std::string face = all[f];
    if (inward) {  // reverse the vertex order
      std::vector<std::string> v;
      for (size_t i = 1; i < face.size() - 1;) {
        const size_t end = face.find(']', i) + 1;
        v.push_back(face.substr(i, end - i));
        i = end + 1;
      }
      face = "[" + v[3] + "," + v[2] + "," + v[1] + "," + v[0] + "]";
    }
    out += (f ? "," : "") + face;
  }
  return out + "]";
}

Scene glass_cube(const std::string& glass, int faces = 6, bool inward = false) {
  return parse_scene(R"({"materials": {"glass": )" + glass +
                         R"(}, "objects": [{"name": "block", "material": "glass", "polygons": )" +
                         cube_polygons(faces, inward) + "}]}",
                     "inline.json");
}

TEST(SceneLoader, ReadsRefraction) {
  // 000 §4: "ior" makes an interface; clear glass unless told otherwise (reflectance 0,
  // transmittance 1); one index or three (dispersion, §4.3).
  const Scene plain = glass_cube(R"({"ior": 1.5})");
  EXPECT_TRUE(fixes(plain).empty()) << fixes(plain).front();
  const Material& m = plain.materials[0];
  ASSERT_TRUE(m.refracts());
  EXPECT_EQ(m.refraction->ior, Rgb(1.5, 1.5, 1.5));
  EXPECT_EQ(m.refraction->transmittance, Rgb::Ones());
  EXPECT_EQ(m.refraction->attenuation, Rgb::Zero());
  EXPECT_FALSE(m.refraction->fresnel || m.refraction->dispersive());
  EXPECT_EQ(m.reflectance, Rgb::Zero());
  EXPECT_FALSE(m.is_filter()) << "a refracting polygon is no filter: its light bends";
  EXPECT_EQ(m.transmittance, Rgb::Zero());

  const Scene prism = glass_cube(
      R"({"ior": [1.51, 1.52, 1.53], "fresnel": true, "attenuation": [0, 0.1, 0.2], "reflectance": 0.02})");
  const Refraction& r = *prism.materials[0].refraction;
  EXPECT_TRUE(r.dispersive() && r.fresnel);
  EXPECT_EQ(r.attenuation, Rgb(0, 0.1, 0.2));
  EXPECT_EQ(prism.materials[0].reflectance, Rgb::Constant(0.02));
  EXPECT_NE(prism.fingerprint(), plain.fingerprint());
  EXPECT_NE(glass_cube(R"({"ior": 1.4})").fingerprint(), plain.fingerprint());

  // The Fresnel transmission at normal incidence (0.96 for n = 1.5) counts against the rest.
  EXPECT_NO_THROW(glass_cube(R"({"ior": 1.5, "fresnel": true, "reflectance": 0.03})"));
  EXPECT_THROW(glass_cube(R"({"ior": 1.5, "fresnel": true, "reflectance": 0.05})"), InputError);
  EXPECT_THROW(glass_cube(R"({"ior": 1.5, "transmittance": 0.9, "reflectance": 0.2})"), InputError);
}

TEST(SceneLoader, ReadsPointLights) {
  // Issue 20: top-level "lights", isotropic, intensity in W/sr (one number for a grey); a
  // light inside a closed object is allowed; the lights enter the fingerprint and the power.
  const std::string floor =
      R"("materials": {"white": {}}, "objects": [{"material": "white", "polygons": )"
      R"([[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]]}])";
  const Scene none = parse_scene("{" + floor + "}", "none.json");
  EXPECT_TRUE(none.lights.empty());
  const Scene two = parse_scene("{" + floor +
                                    R"(, "lights": [{"position": [0.5, 0.5, 1], "intensity": 2},)"
                                    R"( {"position": [0, 0, -1], "intensity": [1, 0, 3]}]})",
                                "two.json");
  ASSERT_EQ(two.lights.size(), 2u);
  EXPECT_EQ(two.lights[0].position, Vec3(0.5, 0.5, 1));
  EXPECT_EQ(two.lights[0].intensity, Rgb::Constant(2));
  EXPECT_EQ(two.lights[1].intensity, Rgb(1, 0, 3));
  const Rgb power = two.light_power();
  EXPECT_NEAR(power[0], 4 * std::numbers::pi * 3, 1e-12);
  EXPECT_NEAR(power[1], 4 * std::numbers::pi * 2, 1e-12);
  EXPECT_NE(two.fingerprint(), none.fingerprint()) << "a solution lit by lights is another";
  EXPECT_THROW(parse_scene("{" + floor + R"(, "lights": {"position": [0, 0, 1]}})", "x.json"),
               InputError);
}

TEST(SceneLoader, ReadsGlossAndSmoothMeshes) {
  // Issue 20: "gloss" (radians, with "specular") and "smooth" (vertex normals: the area-weighted
  // mean of the faces' normals at each shared vertex; 003 warps beams by them).
  const Scene scene = parse_scene(
      R"({"materials": {"brushed": {"reflectance": 0.1, "specular": 0.8, "gloss": 0.15}},)"
      R"( "objects": [{"mesh": "roof.obj", "material": "brushed", "smooth": true},)"
      R"(             {"mesh": "roof.obj", "material": "brushed"}]})",
      kData / "meshes" / "scene.json");
  const Material& m = scene.materials[0];
  EXPECT_TRUE(m.is_glossy() && m.is_mirror());
  EXPECT_EQ(m.gloss, 0.15);
  ASSERT_EQ(scene.polygons.size(), 4u);
  const Polygon& slope = scene.polygons[0];
  ASSERT_EQ(slope.vertex_normals.size(), 4u);
  const double r = 1 / std::sqrt(2.0);
  EXPECT_NEAR((slope.normal - Vec3(0, -r, r)).norm(), 0, 1e-12);
  // On the ridge (vertices 2 and 3) the two slopes' normals average to straight up; at the
  // eaves (0 and 1) only this slope's.
  EXPECT_NEAR((slope.vertex_normals[0] - slope.normal).norm(), 0, 1e-12);
  EXPECT_NEAR((slope.vertex_normals[2] - Vec3(0, 0, 1)).norm(), 0, 1e-12);
  EXPECT_NEAR((slope.vertex_normals[3] - Vec3(0, 0, 1)).norm(), 0, 1e-12);
  EXPECT_TRUE(scene.polygons[2].vertex_normals.empty()) << "not smooth: the face's normal";
  // Interpolated across the face: up on the ridge, the face's at the eaves, between halfway.
  EXPECT_NEAR((shading_normal(slope, Vec3(0.3, 0.5, 0.5)) - Vec3(0, 0, 1)).norm(), 0, 1e-12);
  EXPECT_NEAR((shading_normal(slope, Vec3(0.7, 0, 0)) - slope.normal).norm(), 0, 1e-12);
  const Vec3 half = (slope.normal + Vec3(0, 0, 1)).normalized();
  EXPECT_NEAR((shading_normal(slope, Vec3(0.4, 0.25, 0.25)) - half).norm(), 0, 1e-12);
  EXPECT_EQ(shading_normal(scene.polygons[2], Vec3(0.4, 0.25, 0.25)), scene.polygons[2].normal);
  // "gloss" with "transmittance": a roughened pane, no filter (its light goes into the lobe).
  const Scene pane = parse_scene(
      R"({"materials": {"frosted": {"reflectance": 0, "transmittance": 0.7, "gloss": 0.2}},)"
      R"( "objects": [{"polygons": [[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]], "material": "frosted"}]})",
      "pane.json");
  const Material& frosted = pane.materials[0];
  EXPECT_TRUE(frosted.is_glossy_pane() && frosted.is_glossy() && !frosted.is_glossy_mirror());
  EXPECT_FALSE(frosted.is_filter());
  EXPECT_EQ(frosted.glossy_transmittance, Rgb::Constant(0.7));
}

TEST(SceneLoader, WarnsOfARefractingObjectThatIsNotClosedOrFacesIn) {
  const std::vector<std::string> open = fixes(glass_cube(R"({"ior": 1.5})", 5));
  ASSERT_EQ(open.size(), 1u);
  EXPECT_NE(open[0].find("objects[0] \"block\": refracting but not closed (4 edges"),
            std::string::npos)
      << open[0];
  const std::vector<std::string> inside_out = fixes(glass_cube(R"({"ior": 1.5})", 6, true));
  ASSERT_EQ(inside_out.size(), 1u);
  EXPECT_NE(inside_out[0].find("fronts facing in"), std::string::npos) << inside_out[0];
  // The same open box of an opaque material is a box.
  EXPECT_TRUE(fixes(glass_cube(R"({"reflectance": 0.5})", 5)).empty());
}

TEST(SceneLoader, NonFiniteLiteralsInsideStringsAreLeftAlone) {
  // "NaN" inside a name is text, not a number.
  const Scene scene = parse_scene(R"({"materials": {"m": {}},
      "objects": [{"name": "NaN Infinity", "material": "m", "polygons": [[[0,0,0],[1,0,0],[0,1,0]]]}]})",
                                  "inline.json");
  EXPECT_EQ(scene.objects[0].name, "NaN Infinity");
}

TEST(SceneLoader, RejectsEveryMalformedFileNamingFileAndElement) {
  ASSERT_GE(test::bad_scene_cases().size(), 12u);
  for (const auto& c : test::bad_scene_cases()) {
    const std::filesystem::path file = kData / "bad" / c.file;
    std::string message;
    try {
      load_scene(file);
    } catch (const InputError& e) {
      message = e.what();
    }
    ASSERT_FALSE(message.empty()) << c.file << " loaded without an error";
    EXPECT_NE(message.find(file.string()), std::string::npos) << c.file << ": " << message;
    EXPECT_NE(message.find(c.element), std::string::npos) << c.file << ": " << message;
    EXPECT_NE(message.find(c.problem), std::string::npos) << c.file << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
  }
}

}  // namespace
}  // namespace rad
