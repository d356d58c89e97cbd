// Wavefront OBJ: the polygonal subset (`v` vertices, `f` faces), and which material each face
// takes (`mtllib` libraries, `usemtl` names: MeshMaterials; mtl.h reads the libraries).
// Texture coordinates, normals and groups carry nothing a radiosity scene uses and are skipped;
// lines, points and free-form curves and surfaces are skipped with one warning each, since they
// are geometry a user may have expected to see.
#include <algorithm>
#include <array>
#include <map>
#include <string>

#include "scene/limits.h"
#include "scene/mesh_formats.h"

namespace rad::mesh_formats {

namespace {

/// `mtllib a.mtl b.mtl` names several libraries; a single name with spaces is one library
/// (exporters write "mtllib My Room.mtl"): the words are libraries only when each ends in .mtl.
std::vector<std::string> library_names(std::string_view rest) {
  std::vector<std::string> names;
  Words words(rest);
  for (std::string_view word; words.next(word);) {
    if (lower_extension(std::filesystem::path(word)) != ".mtl") return {std::string(rest)};
    names.emplace_back(word);
  }
  return names;
}

}  // namespace

Faces read_obj(const MeshSource& source, std::vector<std::string>& warnings,
               MeshMaterials& materials) {
  int current_material = -1;  // index into materials.names of the latest usemtl
  std::map<std::string, int, std::less<>> name_index;
  SoupBuilder soup(source, 1);
  Lines lines(source.bytes);
  std::vector<std::string> skipped;  // kinds of geometry skipped, each warned once
  const auto at = [&](const std::string& detail) {
    source.fail("line " + std::to_string(lines.number()) + ": " + detail);
  };
  for (std::string_view line; lines.next(line);) {
    if (const size_t hash = line.find('#'); hash != std::string_view::npos) {
      line = line.substr(0, hash);
    }
    Words words(line);
    std::string_view keyword;
    if (!words.next(keyword)) continue;

    if (keyword == "v") {
      // x y z, then an optional weight or vertex colour, which are not used.
      Vec3 p;
      for (int c = 0; c < 3; ++c) {
        std::string_view word;
        if (!words.next(word)) at("a vertex needs 3 coordinates");
        const auto value = parse_real(word);
        if (!value) at("cannot parse vertex coordinate '" + std::string(word) + "'");
        p[c] = *value;
      }
      soup.add_vertex(p);
    } else if (keyword == "f" || keyword == "fo") {
      // Each corner is v, v/vt, v//vn or v/vt/vn; v counts from 1, or back from the latest
      // vertex when negative (-1 is the vertex just read).
      for (std::string_view corner; words.next(corner);) {
        const std::string_view vertex = corner.substr(0, corner.find('/'));
        const auto index = parse_integer(vertex);
        if (!index || *index == 0) at("cannot parse face corner '" + std::string(corner) + "'");
        if (*index < 0 && -*index > soup.vertex_count()) {
          at("face corner '" + std::string(corner) + "' reaches before the first vertex");
        }
        soup.add_index(*index > 0 ? *index - 1 : soup.vertex_count() + *index);
      }
      soup.end_face();
      materials.face_name.push_back(current_material);
    } else if (keyword == "mtllib") {
      for (std::string& name : library_names(words.rest())) {
        materials.libraries.push_back(std::move(name));
        materials.library_line.push_back(lines.number());
      }
    } else if (keyword == "usemtl") {
      const std::string name(words.rest());
      const auto [known, added] =
          name_index.try_emplace(name, static_cast<int>(materials.names.size()));
      current_material = known->second;
      if (added) {
        materials.names.push_back(name);
        materials.first_line.push_back(lines.number());
      }
    } else {
      static constexpr std::array<std::string_view, 5> kGeometryNotRead{"l", "p", "curv", "curv2",
                                                                        "surf"};
      for (const std::string_view kind : kGeometryNotRead) {
        if (keyword == kind && std::find(skipped.begin(), skipped.end(), kind) == skipped.end()) {
          skipped.emplace_back(kind);
          warnings.push_back(source.where + ": " + source.file + ": '" + std::string(kind) +
                             "' elements (lines, points, curves, surfaces) are not polygons and "
                             "are skipped");
        }
      }
    }
  }
  return soup.take();
}

}  // namespace rad::mesh_formats
