// STL, binary and ASCII. Every facet is kept, in file order: OpenMesh's STL reader, used before,
// merged vertices by position and silently dropped the facets that became degenerate, those
// with NaN coordinates included. Validation happens later, per facet.
#include <cstring>
#include <string>

#include "scene/error.h"
#include "scene/limits.h"
#include "scene/mesh_formats.h"

namespace rad::mesh_formats {

Faces read_stl(const MeshSource& source) {
  const std::string_view bytes = source.bytes;
  Faces faces;
  // Binary STL: 80-byte header, uint32 count, 50 bytes per facet. The size check, not the
  // "solid" keyword, decides: many binary files start their header with "solid".
  if (bytes.size() >= 84) {
    uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    if (bytes.size() == 84 + 50ull * count) {
      source.check_claim(count, "facets", limits::kPolygons, 50, bytes.size() - 84);
      ByteReader in(bytes, 84, /*big_endian=*/false);
      faces.reserve(count);
      for (uint32_t f = 0; f < count; ++f) {
        float data[12];  // the stored normal, then three vertices
        for (float& value : data) in.read(value);
        faces.push_back({Vec3(data[3], data[4], data[5]), Vec3(data[6], data[7], data[8]),
                         Vec3(data[9], data[10], data[11])});
        uint16_t attributes = 0;
        in.read(attributes);
      }
      return faces;
    }
  }
  Lines lines(bytes);
  std::string_view line, word;
  while (lines.next(line) && !Words(line).next(word)) {
  }
  if (!Words(line).next(word) || word != "solid") {
    throw InputError(source.where + ": '" + source.file + "' is neither binary nor ASCII STL");
  }
  std::vector<Vec3> current;
  for (; lines.next(line);) {
    Words words(line);
    if (!words.next(word)) continue;
    if (word == "vertex") {
      Vec3 p;
      for (int c = 0; c < 3; ++c) {
        std::string_view number;
        const auto value = words.next(number) ? parse_real(number) : std::nullopt;
        if (!value) {
          throw InputError(source.where + ": '" + source.file + "' facet " +
                           std::to_string(faces.size()) + ": cannot parse vertex coordinate '" +
                           std::string(number.substr(0, 40)) + "'");
        }
        p[c] = *value;
      }
      if (static_cast<long long>(current.size()) >= limits::kPolygonVertices) {
        source.fail("facet " + std::to_string(faces.size()) + " has more than " +
                    std::to_string(limits::kPolygonVertices) + " vertices");
      }
      current.push_back(p);
    } else if (word == "endloop") {
      if (static_cast<long long>(faces.size()) >= limits::kPolygons) {
        source.fail("more than the limit of " + std::to_string(limits::kPolygons) + " facets");
      }
      faces.push_back(std::move(current));
      current.clear();
    }
  }
  if (faces.empty()) throw InputError(source.where + ": '" + source.file + "' has no facets");
  return faces;
}

}  // namespace rad::mesh_formats
