// OFF (Geomview's Object File Format), ASCII and binary. The keyword [ST][C][N][4][n]OFF says
// what each vertex carries besides x y z: texture coordinates (ST), a colour (C), a normal (N),
// a homogeneous w (4), or a dimension of its own (n, then the dimension). Only the position is
// kept; a 4OFF vertex is x/w y/w z/w. Faces are "n i0 .. i(n-1) [colour]" with 0-based indices.
// ASCII files are read a line per vertex and per face, as OFF files are written (a face's colour
// may have 0 to 4 numbers, so only the line tells where it ends).
#include <string>

#include "scene/limits.h"
#include "scene/mesh_formats.h"

namespace rad::mesh_formats {
namespace {

/// What the keyword says each vertex carries.
struct OffLayout {
  bool texture = false, colour = false, normal = false, homogeneous = false, dimension = false;
  bool binary = false;
};

/// Parses "[ST][C][N][4][n]OFF"; false if the word is not such a keyword.
bool parse_keyword(std::string_view word, OffLayout& layout) {
  const auto take = [&](std::string_view prefix) {
    if (word.substr(0, prefix.size()) != prefix) return false;
    word.remove_prefix(prefix.size());
    return true;
  };
  layout.texture = take("ST");
  layout.colour = take("C");
  layout.normal = take("N");
  layout.homogeneous = take("4");
  layout.dimension = take("n");
  return word == "OFF";
}

/// Lines without comments ('#' to the end of the line) and without blank lines.
class OffLines {
 public:
  explicit OffLines(std::string_view text) : lines_(text) {}
  bool next(std::string_view& line) {
    while (lines_.next(line)) {
      if (const size_t hash = line.find('#'); hash != std::string_view::npos) {
        line = line.substr(0, hash);
      }
      if (line.find_first_not_of(" \t\r\v\f") != std::string_view::npos) return true;
    }
    return false;
  }
  long long number() const { return lines_.number(); }
  size_t offset() const { return lines_.offset(); }

 private:
  Lines lines_;
};

Faces read_ascii(const MeshSource& source, OffLines& lines, Words header_rest,
                 const OffLayout& layout) {
  const auto at = [&](const std::string& detail) {
    source.fail("line " + std::to_string(lines.number()) + ": " + detail);
  };
  // The numbers of the header, which may continue on the keyword's line: [dimension]
  // vertices faces [edges].
  std::vector<long long> header;
  const auto read_header_numbers = [&](Words words) {
    for (std::string_view word; words.next(word);) {
      const auto n = parse_integer(word);
      if (!n) at("cannot parse header count '" + std::string(word) + "'");
      header.push_back(*n);
    }
  };
  read_header_numbers(header_rest);
  const size_t wanted = layout.dimension ? 3 : 2;
  for (std::string_view line; header.size() < wanted && lines.next(line);) {
    read_header_numbers(Words(line));
  }
  if (header.size() < wanted) at("the header has no vertex and face counts");
  if (layout.dimension && header[0] != 3) {
    at("vertices of dimension " + std::to_string(header[0]) + " (only 3 is read)");
  }
  const long long vertices = header[wanted - 2], faces = header[wanted - 1];
  const std::uintmax_t rest = source.bytes.size() - lines.offset();
  source.check_claim(vertices, "vertices", limits::kMeshVertices, 6, rest);       // "0 0 0\n"
  source.check_claim(faces, "faces", limits::kPolygons, 2, rest - 6 * vertices);  // "0\n"

  SoupBuilder soup(source, 0);
  soup.reserve(vertices, faces);
  std::string_view line;
  for (long long v = 0; v < vertices; ++v) {
    if (!lines.next(line)) at("the file ends at vertex " + std::to_string(v));
    Words words(line);
    double xyzw[4] = {0, 0, 0, 1};
    for (int c = 0; c < (layout.homogeneous ? 4 : 3); ++c) {
      std::string_view word;
      if (!words.next(word)) at("vertex " + std::to_string(v) + " has too few coordinates");
      const auto value = parse_real(word);
      if (!value) at("cannot parse vertex coordinate '" + std::string(word) + "'");
      xyzw[c] = *value;
    }
    soup.add_vertex(Vec3(xyzw[0], xyzw[1], xyzw[2]) / xyzw[3]);
  }
  for (long long f = 0; f < faces; ++f) {
    if (!lines.next(line)) at("the file ends at face " + std::to_string(f));
    Words words(line);
    std::string_view word;
    const auto n = words.next(word) ? parse_integer(word) : std::nullopt;
    if (!n || *n < 0) at("face " + std::to_string(f) + " does not start with its vertex count");
    for (long long i = 0; i < *n; ++i) {
      const auto index = words.next(word) ? parse_integer(word) : std::nullopt;
      if (!index)
        at("face " + std::to_string(f) + " has fewer than " + std::to_string(*n) +
           " vertex indices");
      soup.add_index(*index);
    }
    soup.end_face();
  }
  return soup.take();
}

/// Binary OFF (the keyword followed by BINARY, then a newline): big-endian int32 counts,
/// float32 vertex data, and per face an int32 count, its int32 indices, an int32 colour count
/// and that many float32s.
Faces read_binary(const MeshSource& source, size_t offset, const OffLayout& layout) {
  ByteReader in(source.bytes, offset, /*big_endian=*/true);
  const auto truncated = [&](const std::string& what) {
    source.fail("binary data ends in " + what);
  };
  int32_t counts[3];
  if (layout.dimension) {
    int32_t dimension = 0;
    if (!in.read(dimension)) truncated("the header");
    if (dimension != 3) {
      source.fail("vertices of dimension " + std::to_string(dimension) + " (only 3 is read)");
    }
  }
  for (int32_t& c : counts) {
    if (!in.read(c)) truncated("the header");
  }
  // Floats per vertex: position, w, normal, colour (RGBA), texture coordinates.
  const int floats = 3 + (layout.homogeneous ? 1 : 0) + (layout.normal ? 3 : 0) +
                     (layout.colour ? 4 : 0) + (layout.texture ? 2 : 0);
  source.check_claim(counts[0], "vertices", limits::kMeshVertices, 4 * floats, in.remaining());
  source.check_claim(counts[1], "faces", limits::kPolygons, 8,
                     in.remaining() - 4ull * floats * counts[0]);

  SoupBuilder soup(source, 0);
  soup.reserve(counts[0], counts[1]);
  for (int32_t v = 0; v < counts[0]; ++v) {
    float data[13];
    for (int c = 0; c < floats; ++c) {
      if (!in.read(data[c])) truncated("vertex " + std::to_string(v));
    }
    const double w = layout.homogeneous ? data[3] : 1.0;
    soup.add_vertex(Vec3(data[0], data[1], data[2]) / w);
  }
  for (int32_t f = 0; f < counts[1]; ++f) {
    int32_t n = 0, index = 0, colours = 0;
    if (!in.read(n)) truncated("face " + std::to_string(f));
    if (n < 0) source.fail("face " + std::to_string(f) + " has a negative vertex count");
    for (int32_t i = 0; i < n; ++i) {
      if (!in.read(index)) truncated("face " + std::to_string(f));
      soup.add_index(index);
    }
    soup.end_face();
    if (!in.read(colours)) truncated("face " + std::to_string(f));
    if (colours < 0 || colours > 4) {
      source.fail("face " + std::to_string(f) + " has " + std::to_string(colours) +
                  " colour components (0 to 4)");
    }
    float colour = 0;
    for (int32_t c = 0; c < colours; ++c) {
      if (!in.read(colour)) truncated("face " + std::to_string(f));
    }
  }
  return soup.take();
}

}  // namespace

Faces read_off(const MeshSource& source) {
  OffLines lines(source.bytes);
  std::string_view line, word;
  if (!lines.next(line)) source.fail("the file is empty");
  Words words(line);
  OffLayout layout;
  if (!words.next(word) || !parse_keyword(word, layout)) {
    source.fail("line " + std::to_string(lines.number()) + ": expected the keyword OFF, found '" +
                std::string(line.substr(0, 40)) + "'");
  }
  Words after_keyword = words;
  if (words.next(word) && word == "BINARY") {
    // The binary data starts just after the keyword's line.
    if (words.next(word)) source.fail("line 1: unexpected '" + std::string(word) + "'");
    return read_binary(source, lines.offset(), layout);
  }
  return read_ascii(source, lines, after_keyword, layout);
}

}  // namespace rad::mesh_formats
