// A user's own scene (issue 39): OBJ materials (MTL) into scene materials, an OBJ alone as a
// scene, and a room whose fronts face out. The translation is checked against values written
// by hand from the table in docs/formats.md, and a whole room against the same room written
// as a scene file by hand (tests/data/obj-room/README.md).
#include "scene/mtl.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "scene/error.h"
#include "scene/scene_loader.h"
#include "tests/scratch_dir.h"

namespace rad {
namespace {

const std::filesystem::path kRoom = std::filesystem::path(RAD_TEST_DATA) / "obj-room";

Material only(const std::string& text, std::vector<std::string>* warnings_out = nullptr) {
  std::vector<std::string> warnings;
  const MaterialLibrary library = parse_material_library(text, "t.mtl", warnings);
  EXPECT_EQ(library.size(), 1u);
  if (warnings_out)
    *warnings_out = warnings;
  else
    EXPECT_TRUE(warnings.empty()) << warnings.front();
  return library.begin()->second;
}

bool contains(const std::vector<std::string>& lines, const std::string& part) {
  for (const std::string& line : lines)
    if (line.find(part) != std::string::npos) return true;
  return false;
}

void write(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

TEST(Mtl, DiffuseAndEmissionAsTheTableSays) {
  // Kd is the reflectance; Ke a radiance, so the exitance is pi Ke.
  const Material m = only("newmtl lamp\nKd 0.2 0.3 0.4\nKe 1 2 3\n");
  EXPECT_EQ(m.name, "lamp");
  EXPECT_EQ(m.reflectance, Rgb(0.2, 0.3, 0.4));
  EXPECT_NEAR(m.emission[0], std::numbers::pi, 1e-15);
  EXPECT_NEAR(m.emission[2], 3 * std::numbers::pi, 1e-15);
  EXPECT_FALSE(m.is_filter() || m.is_mirror() || m.refracts());
  // One number is a grey (the MTL default for g and b).
  EXPECT_EQ(only("newmtl g\nKd 0.25\n").reflectance, Rgb(0.25, 0.25, 0.25));
  // Without Kd, the scene file's default.
  EXPECT_EQ(only("newmtl g\nKe 0 0 0\n").reflectance, Rgb(0.5, 0.5, 0.5));
}

TEST(Mtl, DissolveAndFilterMakeATransmittance) {
  // d = 0.25 opaque: a quarter of Kd reflects, three quarters pass through Tf.
  const Material m = only("newmtl pane\nKd 0.8 0.8 0.8\nd 0.25\nTf 1 0.5 0\n");
  EXPECT_NEAR(m.reflectance[0], 0.2, 1e-15);
  EXPECT_NEAR(m.transmittance[0], 0.75, 1e-15);
  EXPECT_NEAR(m.transmittance[1], 0.375, 1e-15);
  EXPECT_EQ(m.transmittance[2], 0);
  // Tr is 1 - d; "d -halo" is still a dissolve.
  EXPECT_NEAR(only("newmtl a\nKd 0.4\nTr 0.5\n").transmittance[1], 0.5, 1e-15);
  EXPECT_NEAR(only("newmtl a\nKd 0.4\nd -halo 0.5\n").transmittance[1], 0.5, 1e-15);
  // Opaque (d 1, Tf 1: what every exporter writes) passes nothing.
  EXPECT_FALSE(only("newmtl a\nKd 0.4\nd 1\nTf 1 1 1\n").is_filter());
}

TEST(Mtl, SpecularOnlyWhenIllumReflects) {
  // illum 2 is a Phong highlight: Ks has no part in a radiosity solution.
  EXPECT_FALSE(only("newmtl a\nKd 0.3\nKs 0.5\nNs 250\nillum 2\n").is_mirror());
  // illum 3 reflects: Ks is the mirror's reflectance, Ns the lobe: sigma = 1 / sqrt(Ns).
  const Material glossy = only("newmtl a\nKd 0.3\nKs 0.5\nNs 100\nillum 3\n");
  EXPECT_EQ(glossy.specular, Rgb(0.5, 0.5, 0.5));
  EXPECT_NEAR(glossy.gloss, 0.1, 1e-15);
  // Ns 1000 (Blender's smooth) and no Ns at all: a perfect mirror.
  EXPECT_EQ(only("newmtl a\nKd 0.3\nKs 0.5\nNs 1000\nillum 3\n").gloss, 0);
  EXPECT_EQ(only("newmtl a\nKd 0.3\nKs 0.5\nillum 3\n").gloss, 0);
  // Ns 0: the widest lobe the scene allows.
  EXPECT_NEAR(only("newmtl a\nKd 0.3\nKs 0.5\nNs 0\nillum 3\n").gloss, std::numbers::pi, 1e-15);
}

TEST(Mtl, GlassRefractsWithNi) {
  const Material glass = only("newmtl glass\nKd 0 0 0\nNi 1.5\nTf 0.9 0.9 0.9\nillum 4\n");
  ASSERT_TRUE(glass.refracts());
  EXPECT_EQ(glass.refraction->ior, Rgb(1.5, 1.5, 1.5));
  EXPECT_EQ(glass.refraction->transmittance, Rgb(0.9, 0.9, 0.9));
  EXPECT_FALSE(glass.refraction->fresnel);
  EXPECT_TRUE(only("newmtl g\nKd 0\nNi 1.33\nillum 7\n").refraction->fresnel);
  // Ni on an opaque material (Blender writes Ni 1.45 everywhere) refracts nothing.
  EXPECT_FALSE(only("newmtl a\nKd 0.4\nNi 1.45\nillum 2\n").refracts());
}

TEST(Mtl, ScalesWhatNoSurfaceCanSendOnWithAWarning) {
  std::vector<std::string> warnings;
  // Kd 1: reflects all it receives; kept just below 1.
  const Material white = only("newmtl w\nKd 1 1 1\n", &warnings);
  EXPECT_NEAR(white.reflectance[0], 0.99, 1e-15);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("t.mtl line 1: material 'w'"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("scaled by 0.99"), std::string::npos) << warnings[0];
  // Kd + Ks = 1.6 with reflection on: both scaled by 1 / 1.6.
  const Material both = only("newmtl m\nKd 0.8\nKs 0.8\nillum 3\n", &warnings);
  EXPECT_NEAR(both.reflectance[0] + both.specular[0], 1, 1e-15);
  EXPECT_NEAR(both.reflectance[0], 0.5, 1e-15);
  EXPECT_EQ(warnings.size(), 1u);
}

TEST(Mtl, MalformedStatementsNameTheLine) {
  struct Case {
    const char* text;
    const char* message;
  };
  for (const Case& c : {
           Case{"Kd 0.5\n", "t.mtl line 1: 'Kd' before the first 'newmtl'"},
           Case{"newmtl a\nKd 0.5 0.5\n", "t.mtl line 2: 'Kd' needs 1 or 3 numbers, has 2"},
           Case{"newmtl a\n\nKe nan 1 1\n", "t.mtl line 3: cannot parse 'Ke'"},
           Case{"newmtl a\nKe -1 0 0\n", "t.mtl line 2: 'Ke' is negative"},
           Case{"newmtl a\nd 1.5\n", "t.mtl line 2: 'd' is outside [0, 1]"},
           Case{"newmtl a\nillum 2.5\n", "t.mtl line 2: 'illum' is not an illumination model"},
           Case{"newmtl a\nKd spectral x.rfl\n", "'Kd spectral' colours are not supported"},
           Case{"newmtl a\nTf 2 2 2\n", "t.mtl line 1: material 'a': 'Tf' is above 1"},
       }) {
    std::vector<std::string> warnings;
    try {
      parse_material_library(c.text, "t.mtl", warnings);
      ADD_FAILURE() << "accepted: " << c.text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos)
          << e.what() << "\nexpected: " << c.message;
    }
  }
}

TEST(Mtl, SaysWhatItSkipsOrReplaces) {
  std::vector<std::string> warnings;
  const MaterialLibrary library = parse_material_library(
      "newmtl a\nKd 0.1\nmap_Kd a.png\nmap_Ks b.png\nnewmtl a\nKd 0.2\n", "t.mtl", warnings);
  ASSERT_EQ(library.size(), 1u);
  EXPECT_EQ(library.at("a").reflectance[0], 0.2);  // the later definition
  ASSERT_EQ(warnings.size(), 2u);                  // textures once, the redefinition once
  EXPECT_NE(warnings[0].find("'map_Kd' texture maps are not used"), std::string::npos);
  EXPECT_NE(warnings[1].find("defined again (first at line 1)"), std::string::npos);
}

TEST(ObjScene, ARoomTakesItsMaterialsAsTheSameRoomWrittenByHand) {
  const Scene obj = load_scene(kRoom / "room.obj");
  const Scene json = load_scene(kRoom / "room.json");
  EXPECT_TRUE(obj.warnings.empty()) << obj.warnings.front();
  ASSERT_EQ(obj.polygons.size(), json.polygons.size());
  // Same vertices, same material values face by face: one fingerprint.
  EXPECT_EQ(obj.fingerprint(), json.fingerprint());
  for (size_t i = 0; i < obj.polygons.size(); ++i) {
    EXPECT_EQ(obj.materials[obj.polygons[i].material].name,
              json.materials[json.polygons[i].material].name);
  }
  EXPECT_EQ(obj.emitter_count(), 1);
  // A camera from the bounds: inside the closed room, looking at its middle.
  ASSERT_TRUE(obj.camera);
  EXPECT_EQ(obj.camera->look_at, Vec3(2, 1.5, 2));
  EXPECT_GT(obj.camera->eye.z(), 2);
  EXPECT_LT(obj.camera->eye.z(), 4);
  // A scene file naming the OBJ without "material" takes the same materials.
  const Scene named = load_scene(kRoom / "scene.json");
  EXPECT_EQ(named.fingerprint(), obj.fingerprint());
  EXPECT_TRUE(named.warnings.empty()) << named.warnings.front();
  // A material of the scene file's own with a usemtl's name takes that name's faces.
  const std::filesystem::path dir = test::scratch_dir("obj_named");
  write(dir / "s.json", R"({"materials": {"Lamp": {"emission": [2, 2, 2]}},
                           "objects": [{"mesh": ")" +
                            (kRoom / "room.obj").string() + R"("}]})");
  const Scene relit = load_scene(dir / "s.json");
  EXPECT_EQ(relit.emitted_power(), Rgb(2, 2, 2));  // the lamp's 1 m^2 at 2 W/m^2
  EXPECT_EQ(relit.materials[relit.polygons[0].material].name, "Floor");  // from room.mtl
}

TEST(ObjScene, ARoomFacingOutWarnsAndFlipsBack) {
  const Scene outward = load_scene(kRoom / "room-outward.obj");
  ASSERT_EQ(outward.warnings.size(), 1u);
  EXPECT_NE(outward.warnings[0].find("no polygon faces a light"), std::string::npos);
  EXPECT_NE(outward.warnings[0].find("--flip-normals"), std::string::npos);
  // Seen from the middle, the walls show their backs: the camera stands outside.
  EXPECT_GT(outward.camera->eye.z(), 4);
  SceneOptions flip;
  flip.flip_normals = true;
  const Scene turned = load_scene(kRoom / "room-outward.obj", nullptr, flip);
  EXPECT_TRUE(turned.warnings.empty()) << turned.warnings.front();
  EXPECT_EQ(turned.fingerprint(), load_scene(kRoom / "room.obj").fingerprint());
  // Turning the right room makes it the wrong one.
  EXPECT_FALSE(load_scene(kRoom / "room.obj", nullptr, flip).warnings.empty());
}

TEST(ObjScene, AScenePointLightLightingNothingWarnsToo) {
  const std::filesystem::path dir = test::scratch_dir("obj_point_light");
  // A floor facing down with a point light above it: its front never sees the light.
  write(dir / "s.json",
        R"({"materials": {"m": {}}, "lights": [{"position": [0, 1, 0], "intensity": [1, 1, 1]}],
            "objects": [{"material": "m", "polygons": [[[0, 0, 0], [1, 0, 0], [1, 0, 1]]]}]})");
  EXPECT_TRUE(contains(load_scene(dir / "s.json").warnings, "no polygon faces a light"));
  write(
      dir / "dark.json",
      R"({"materials": {"m": {}}, "objects": [{"material": "m", "polygons": [[[0, 0, 0], [1, 0, 0], [1, 0, 1]]]}]})");
  EXPECT_TRUE(contains(load_scene(dir / "dark.json").warnings, "nothing emits light"));
}

TEST(ObjScene, MissingLibrariesAndNamesGoGreyWithAWarning) {
  const std::filesystem::path dir = test::scratch_dir("obj_materials");
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  write(dir / "lib.mtl", "newmtl lamp\nKe 1 1 1\nKd 0\n");
  write(dir / "a.obj", "mtllib lib.mtl gone.mtl\n" + square +
                           "f 1 2 3\nusemtl lamp\nf 1 3 4\nusemtl nowhere\nf 1 2 4\n");
  const Scene scene = load_scene(dir / "a.obj");
  ASSERT_EQ(scene.polygons.size(), 3u);
  EXPECT_EQ(scene.materials[scene.polygons[0].material].name, "grey (no material)");
  EXPECT_EQ(scene.materials[scene.polygons[1].material].name, "lamp");
  EXPECT_EQ(scene.materials[scene.polygons[2].material].name, "grey (no material)");
  EXPECT_TRUE(contains(scene.warnings, "gone.mtl: cannot open material library"));
  EXPECT_TRUE(contains(scene.warnings,
                       "line 9: material 'nowhere' is in none of lib.mtl, "
                       "gone.mtl: its 1 face is grey"));
  EXPECT_TRUE(contains(scene.warnings, "1 face before the first usemtl"));
  // A scene file's "material" replaces the OBJ's own: the libraries are not read.
  write(dir / "s.json",
        R"({"materials": {"m": {}}, "objects": [{"mesh": "a.obj", "material": "m"}]})");
  for (const std::string& w : load_scene(dir / "s.json").warnings)
    EXPECT_EQ(w.find("gone.mtl"), std::string::npos) << w;
  // Library names with spaces; a malformed library is an error naming its line.
  write(dir / "My Room.mtl", "newmtl lamp\nKe 1 1 1\nKd 0 0\n");
  write(dir / "b.obj", "mtllib My Room.mtl\n" + square + "usemtl lamp\nf 1 2 3 4\n");
  EXPECT_THROW(
      {
        try {
          load_scene(dir / "b.obj");
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("My Room.mtl line 3: 'Kd' needs 1 or 3"),
                    std::string::npos)
              << e.what();
          throw;
        }
      },
      InputError);
  // Only an OBJ names its materials: a PLY object still needs one.
  write(dir / "p.json", R"({"objects": [{"mesh": "x.ply"}]})");
  try {
    load_scene(dir / "p.json");
    ADD_FAILURE() << "a PLY object without a material loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing \"material\" (only an OBJ mesh names its own)"),
              std::string::npos)
        << e.what();
  }
}

TEST(ObjScene, FacesOfNoAreaInAMeshAreLeftOutAndCounted) {
  const std::filesystem::path dir = test::scratch_dir("obj_slivers");
  write(dir / "a.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\nf 1 1 2\nf 3 3 3\nf 1 2\n");
  const Scene scene = load_scene(dir / "a.obj");
  EXPECT_EQ(scene.polygons.size(), 1u);
  EXPECT_TRUE(contains(scene.warnings, "left out 4 faces of no area"));
  EXPECT_TRUE(contains(scene.warnings, "from face 1 on"));
}

// Debian's assimp-testmodels (installed by make test): every OBJ that names a material library
// loads with its materials, or fails with one line naming the file and the face.
TEST(ObjScene, AssimpTestModels) {
  const std::filesystem::path models = "/usr/share/assimp/models/OBJ";
  ASSERT_TRUE(std::filesystem::is_directory(models))
      << "install assimp-testmodels (scripts/install-deps.sh test does)";
  int loaded = 0;
  for (const auto& entry : std::filesystem::directory_iterator(models)) {
    if (entry.path().extension() != ".obj") continue;
    std::ifstream in(entry.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.find("mtllib") == std::string::npos) continue;
    try {
      const Scene scene = load_scene(entry.path());
      ++loaded;
      EXPECT_TRUE(scene.camera) << entry.path();
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      EXPECT_EQ(message.rfind(entry.path().string(), 0), 0u) << message;
    }
  }
  EXPECT_GE(loaded, 6);
  // What the files say, read by hand: box_spaces.mtl's "Door" is Kd 0.8 0.6 0.4, Ks 0.9 with
  // illum 2 (a highlight); "Windows" is Kd 0.6 0.7 0.8 with d 0.5.
  const Scene box = load_scene(models / "regr01.obj");
  int doors = 0, windows = 0;
  for (const Polygon& p : box.polygons) {
    const Material& m = box.materials[p.material];
    if (m.name == "Door") {
      ++doors;
      EXPECT_EQ(m.reflectance, Rgb(0.8, 0.6, 0.4));
      EXPECT_FALSE(m.is_mirror());
    }
    if (m.name == "Windows") {
      ++windows;
      EXPECT_NEAR(m.reflectance[2], 0.4, 1e-15);
      EXPECT_NEAR(m.transmittance[2], 0.5, 1e-15);
    }
  }
  EXPECT_GT(doors, 0);
  EXPECT_GT(windows, 0);
  // cube_usemtl: Kd 1 is scaled below 1, and 'mtl3' is in no library.
  const Scene cube = load_scene(models / "cube_usemtl.obj");
  EXPECT_TRUE(contains(cube.warnings, "material 'mtl': reflects 1"));
  EXPECT_TRUE(contains(cube.warnings, "material 'mtl3' is in none of cube_usemtl.mtl"));
}

}  // namespace
}  // namespace rad
