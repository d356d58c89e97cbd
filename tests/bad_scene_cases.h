#pragma once
/// The malformed scene files of tests/data/bad/, one per error class of DESIGN.md §5, with the
/// words each message must contain. Shared by the loader test (in process) and the CLI test
/// (exit code 1 and the message on stderr).
#include <string>
#include <vector>

namespace rad::test {

struct BadSceneCase {
  std::string file;     ///< under tests/data/bad/
  std::string element;  ///< the element the message must name
  std::string problem;  ///< the words describing the problem
};

inline const std::vector<BadSceneCase>& bad_scene_cases() {
  static const std::vector<BadSceneCase> cases{
      {"invalid_json.json", "invalid_json.json:2:", "invalid JSON"},
      {"unknown_key.json", "objects[0]", "unknown key \"colour\""},
      {"unknown_material.json", "objects[0] \"wall\"", "unknown material \"marble\""},
      {"reflectance_2.json", "materials.\"white\"", "reflectance[1] = 2 is outside [0, 1)"},
      {"negative_emission.json", "materials.\"lamp\"", "emission[1] = -1 is negative"},
      {"transmittance_1.2.json", "materials.\"glass\"", "transmittance[1] = 1.2 is outside [0, 1]"},
      {"negative_specular.json", "materials.\"mirror\"", "specular[0] = -0.1 is outside [0, 1]"},
      {"specular_and_reflectance.json", "materials.\"mirror\"",
       "reflectance + transmittance + specular = 1.1 in channel 0 exceeds 1"},
      {"negative_mirror_depth.json", "mirror_depth", "expected an integer from 0 to 8"},
      {"ior_below_1.json", "materials.\"glass\"", "ior[0] = 0.8 is below 1"},
      {"negative_attenuation.json", "materials.\"glass\"", "attenuation[1] = -0.2 is negative"},
      {"fresnel_and_transmittance.json", "materials.\"glass\"",
       "has both \"transmittance\" and \"fresnel\": true"},
      {"attenuation_without_ior.json", "materials.\"white\"", "has \"attenuation\" but no \"ior\""},
      {"fresnel_not_boolean.json", "materials.\"glass\".fresnel", "expected true or false"},
      {"refraction_depth_9.json", "refraction_depth", "expected an integer from 0 to 8"},
      {"transmittance_with_default_reflectance.json", "materials.\"glass\"",
       "reflectance is 0.5 when omitted"},
      {"nan_coordinate.json", "objects[0] polygon 1 vertex 2[0]", "not a finite number (NaN)"},
      {"infinite_coordinate.json", "objects[0] polygon 0 vertex 1[0]",
       "not a finite number (Infinity)"},
      {"nan_in_stl.json", "objects[0] (nan.stl) face 1", "vertex 2 is not finite"},
      {"nan_in_mesh.json", "objects[0] (nan.off) face 0", "vertex 2 is not finite"},
      {"two_vertices.json", "objects[0] polygon 2", "has 2 vertices"},
      {"zero_area.json", "objects[0] polygon 0", "zero area"},
      {"non_planar.json", "objects[0] polygon 0", "is not planar"},
      {"self_intersecting.json", "objects[0] polygon 0", "self-intersecting"},
      {"missing_mesh.json", "objects[0] (no-such-file.obj)", "cannot open mesh file"},
      {"unsupported_mesh.json", "objects[0] (points.xyz)", "unsupported mesh format '.xyz'"},
      {"unreadable_mesh.json", "objects[0] (garbage.ply)", "cannot read mesh file"},
      {"bad_camera.json", "camera", "up is zero or parallel to the view direction"},
      {"wrong_type.json", "objects[0] polygon 0 vertex 2", "expected [x, y, z]"},
      {"mesh_and_polygons.json", "objects[0]", "exactly one of \"mesh\" or \"polygons\""},
      {"no_objects.json", "top level", "missing \"objects\""},
      {"nan_light_position.json", "lights[1].position[1]", "not a finite number (NaN)"},
      {"negative_light_intensity.json", "lights[0]", "intensity[1] = -2 is negative"},
      {"light_without_intensity.json", "lights[0]", "missing \"intensity\""},
      {"negative_gloss.json", "materials.\"brushed\".gloss", "gloss = -0.1 is outside [0, pi]"},
      {"gloss_without_specular.json", "materials.\"matte\"",
       "has \"gloss\" but no \"specular\" or \"transmittance\""},
      {"smooth_polygons.json", "objects[0]", "\"smooth\" needs a \"mesh\""},
      {"does_not_exist.json", "does_not_exist.json", "cannot open scene file"},
  };
  return cases;
}

}  // namespace rad::test
