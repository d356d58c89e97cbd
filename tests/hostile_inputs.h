#pragma once
/// Malformed and hostile inputs, one per class (issue 16), each run through the executable by
/// tests/cli/hostile_input_test.cpp: exit 1, one line on stderr naming the file (or option) and
/// the problem, no crash, no hang, nothing written. With the malformed scenes of
/// tests/bad_scene_cases.h (run the same way by cli_test.cpp) they make the table of
/// docs/robustness.md. Placeholders in `command`: {h} tests/data/hostile, {b} tests/data/bad,
/// {d} data, {f} fuzz/regressions, {g} the inputs the test generates, {o} an empty output
/// folder, {s} a solution of the Cornell box.
#include <string>
#include <vector>

namespace rad::test {

struct HostileInput {
  std::string what;     ///< the class of input
  std::string command;  ///< radiosity's arguments
  std::string names;    ///< what the message must name (a file, an element, an option)
  std::string problem;  ///< words of the message
};

inline const std::vector<HostileInput>& hostile_inputs() {
  static const std::vector<HostileInput> cases{
      // Scene files
      {"JSON nested 100,000 deep", "info {g}/deep.json",
       "deep.json:1:", "nested deeper than 64 levels"},
      {"empty scene file", "info {h}/empty.json", "empty.json", "invalid JSON"},
      {"binary bytes as a scene", "info {h}/binary.json", "binary.json", "invalid JSON"},
      {"truncated scene file", "info {h}/truncated.json", "truncated.json", "invalid JSON"},
      {"a JSON array as the scene", "info {h}/top_level_array.json", "top level",
       "expected an object"},
      {"camera of 100000 x 100000", "info {h}/huge_camera.json", "camera.width",
       "more than the limit of 32768"},
      {"camera image larger than memory",
       "render {h}/camera_memory.json --method albedo -o {o}/a.exr", "camera_memory.json: camera",
       "GiB, more than half of this machine's"},
      {"--width/--height larger than memory",
       "render {d}/cornell-box/scene.json --method albedo --width 32768 --height 32768 -o "
       "{o}/a.exr",
       "render --width/--height", "GiB, more than half of this machine's"},
      {"materials not an object", "info {h}/materials_not_object.json", "materials",
       "expected an object"},
      {"objects not a list", "info {h}/objects_not_array.json", "objects", "expected a list"},
      {"polygons not a list", "info {h}/polygons_not_array.json", "polygons", "expected a list"},
      {"coordinate 1e400", "info {h}/huge_number.json", "huge_number.json", "number"},
      {"reflectance as a word", "info {h}/string_reflectance.json", "reflectance", "expected"},
      {"reflectance of four channels", "info {h}/reflectance_four.json", "reflectance", "expected"},
      {"negative camera width", "info {h}/negative_width.json", "camera.width",
       "expected a positive integer"},
      {"field of view 0", "info {h}/fov_zero.json", "camera", "fov"},
      {"object name a number", "info {h}/name_not_string.json", "objects[0].name",
       "expected a string"},
      {"empty polygon", "info {h}/empty_polygon.json", "objects[0] \"floor\" polygon 0",
       "vertices"},
      {"object without material", "info {h}/missing_material_key.json", "objects[0]",
       "missing \"material\""},
      {"unknown top-level key", "info {h}/unknown_top_key.json", "top level",
       "unknown key \"sun\""},
      {"polygon of 100,001 vertices", "info {g}/many_vertices.json", "polygon 0",
       "more than 100000"},
      {"scene file over 256 MiB", "info {g}/huge.json", "huge.json",
       "more than the limit of 256 MiB"},
      // Mesh files, through a scene that names them
      {"mesh path is a folder", "info {h}/mesh_is_directory.json", "folder.obj",
       "cannot open mesh file"},
      {"OBJ face index out of range", "info {h}/obj_index_out_of_range.json",
       "index_out_of_range.obj", "face"},
      {"OBJ of garbage", "info {h}/obj_garbage.json", "garbage.obj", "no readable faces"},
      {"empty OBJ", "info {h}/obj_empty.json", "empty.obj", "no readable faces"},
      {"PLY claiming 4 billion vertices", "info {h}/ply_claims_billions.json",
       "claims_billions.ply", "claims"},
      {"truncated binary PLY", "info {h}/ply_truncated_binary.json", "truncated_binary.ply",
       "claims 3 vertices, more than its 5 bytes hold"},
      {"OFF with negative counts", "info {h}/off_negative_counts.json", "negative_counts.off",
       "claims a negative count"},
      {"OFF claiming 3 billion vertices", "info {h}/off_claims_billions.json",
       "claims_billions.off", "claims"},
      {"OFF face index out of range", "info {h}/off_face_out_of_range.json",
       "face_out_of_range.off", "face"},
      {"truncated binary STL", "info {h}/stl_truncated_binary.json", "truncated_binary.stl",
       "neither binary nor ASCII STL"},
      {"empty STL", "info {h}/stl_empty.json", "empty.stl", "STL"},
      {"OBJ face corner '//1/' (aborted OpenMesh's reader)", "info {g}/obj_fuzz_crash.json",
       "obj_fuzz_crash.obj", "line 6: cannot parse face corner"},
      {"PLY header with a broken format line (hung OpenMesh's reader)",
       "info {g}/ply_fuzz_timeout.json", "ply_fuzz_timeout.ply", "expected one 'format"},
      {"OBJ coordinate of 100,000 characters", "info {g}/obj_long_word.json", "obj_long_word.obj",
       "line 1: cannot parse vertex coordinate 'xxxx"},
      {"binary OFF claiming 500 million vertices", "info {g}/off_binary_claims.json",
       "off_binary_claims.off", "claims 500000000 vertices, more than the limit"},
      // Probe points
      {"binary bytes as points", "probe {d}/cornell-box/scene.json -s {s} --points {h}/binary.csv",
       "binary.csv:", "expected 6 fields"},
      {"NaN in a point", "probe {d}/cornell-box/scene.json -s {s} --points {h}/nan.csv",
       "nan.csv:2", "not finite"},
      {"a line of 60,000 fields",
       "probe {d}/cornell-box/scene.json -s {s} --points {h}/long_line.csv", "long_line.csv:1",
       "expected 6 fields x,y,z,nx,ny,nz, got 60001"},
      {"missing points file", "probe {d}/cornell-box/scene.json -s {s} --points {h}/none.csv",
       "none.csv", "cannot open"},
      // Solution files
      {"truncated solution",
       "render {d}/cornell-box/scene.json --method patches -s {h}/truncated.vtp -o {o}/p.exr",
       "truncated.vtp", "claims more data than the file holds"},
      {"corrupt compressed solution",
       "render {d}/cornell-box/scene.json --method patches -s {h}/corrupt_payload.vtp -o {o}/p.exr",
       "corrupt_payload.vtp", "solution"},
      {"solution claiming 1e11 tuples",
       "render {d}/cornell-box/scene.json --method patches -s {h}/huge_claim.vtp -o {o}/p.exr",
       "huge_claim.vtp", "claims more than"},
      {"empty solution file",
       "render {d}/cornell-box/scene.json --method patches -s {h}/empty.vtp -o {o}/p.exr",
       "empty.vtp", "not a VTK XML PolyData"},
      {"text as a solution",
       "render {d}/cornell-box/scene.json --method patches -s {h}/text.vtp -o {o}/p.exr",
       "text.vtp", "not a VTK XML PolyData"},
      {"a foreign .vtp",
       "render {d}/cornell-box/scene.json --method patches -s {h}/foreign.vtp -o {o}/p.exr",
       "foreign.vtp", "not a solution file"},
      {"solution with a misspelled element (crashed VTK's reader)",
       "render {d}/cornell-box/scene.json --method patches "
       "-s {f}/fuzz_solution/fuzz_solution-crash-ee6655ee55046fc348a4585a28a5aa10d4a38827 "
       "-o {o}/p.exr",
       "FieldData/Arra", "unexpected element <Arra>"},
      {"solution array of unknown type (crashed VTK's reader)",
       "render {d}/cornell-box/scene.json --method patches "
       "-s {f}/fuzz_solution/fuzz_solution-crash-8e2450ce73a8993e920d9e5e29ecce279ad6a43e "
       "-o {o}/p.exr",
       "DataArray[0] \"ambient\"", "unknown type \"Float28\""},
      {"solution naming a polygon its scene lacks",
       "render {d}/cornell-box/scene.json --method patches -s {g}/wrong_polygon.vtp -o {o}/p.exr",
       "wrong_polygon.vtp", "names polygon 20; the scene has 20"},
      {"solution with a NaN radiosity",
       "render {d}/cornell-box/scene.json --method patches -s {g}/nan_radiosity.vtp -o {o}/p.exr",
       "nan_radiosity.vtp", "is not finite"},
      {"solution of another scene",
       "render {d}/light-over-floor/scene.json --method patches -s {s} -o {o}/p.exr",
       "solution.vtp", "solved for a different scene"},
      // Images
      {"truncated EXR", "compare {h}/truncated.exr {h}/truncated.exr", "truncated.exr", "EXR"},
      {"empty EXR", "compare {h}/empty.exr {h}/empty.exr", "empty.exr", "EXR"},
      {"PNG named .exr", "compare {h}/png_renamed.exr {h}/png_renamed.exr", "png_renamed.exr",
       "EXR"},
      {"missing image", "compare {h}/none.exr {h}/none.exr", "none.exr",
       "cannot open image file: No such file"},
      // Outputs
      {"output under a file",
       "render {d}/cornell-box/scene.json --method albedo -o {h}/empty.json/a.exr", "a.exr",
       "cannot"},
      {"solution output under a file",
       "solve {d}/closed-cube/scene.json --patch-size 0.5 -o {h}/empty.json/s.vtp", "s.vtp",
       "cannot create folder"},
      {"solution output a folder", "solve {d}/closed-cube/scene.json --patch-size 0.5 -o {h}",
       "hostile", "is a folder"},
  };
  return cases;
}

}  // namespace rad::test
