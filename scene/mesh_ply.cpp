// PLY (Stanford polygon file), ASCII and binary of either byte order. The header declares
// elements, each a count and a list of properties (scalars, or lists with a count type and an
// item type); the body holds the elements in that order. Kept: x y z of `vertex` and the list
// `vertex_indices` (or `vertex_index`) of `face`; every other property and element is read past.
#include <cstdint>
#include <string>

#include "scene/limits.h"
#include "scene/mesh_formats.h"

namespace rad::mesh_formats {
namespace {

enum class Type { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

/// The type a PLY type name means (both the old "uchar" and the new "uint8" names), if any.
std::optional<Type> parse_type(std::string_view name) {
  struct Named {
    std::string_view old_name, new_name;
    Type type;
  };
  static constexpr Named kTypes[] = {
      {"char", "int8", Type::kInt8},        {"uchar", "uint8", Type::kUint8},
      {"short", "int16", Type::kInt16},     {"ushort", "uint16", Type::kUint16},
      {"int", "int32", Type::kInt32},       {"uint", "uint32", Type::kUint32},
      {"float", "float32", Type::kFloat32}, {"double", "float64", Type::kFloat64}};
  for (const Named& t : kTypes) {
    if (name == t.old_name || name == t.new_name) return t.type;
  }
  return std::nullopt;
}

size_t size_of(Type type) {
  switch (type) {
    case Type::kInt8:
    case Type::kUint8:
      return 1;
    case Type::kInt16:
    case Type::kUint16:
      return 2;
    case Type::kInt32:
    case Type::kUint32:
    case Type::kFloat32:
      return 4;
    case Type::kFloat64:
      return 8;
  }
  return 0;
}

bool is_integer(Type type) { return type != Type::kFloat32 && type != Type::kFloat64; }

struct Property {
  std::string name;
  Type type = Type::kFloat32;           ///< of the scalar, or of a list's items
  std::optional<Type> list_count_type;  ///< set for a list
};

struct Element {
  std::string name;
  long long count = 0;
  std::vector<Property> properties;
  /// Fewest bytes one instance takes in the body: in binary, every scalar and list count; in
  /// ASCII, a digit and a separator per property.
  std::uintmax_t min_bytes(bool binary) const {
    std::uintmax_t bytes = 0;
    for (const Property& p : properties) {
      bytes += binary ? size_of(p.list_count_type.value_or(p.type)) : 2;
    }
    return bytes;
  }
};

enum class Format { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

struct Header {
  Format format = Format::kAscii;
  std::vector<Element> elements;
  size_t body = 0;  ///< offset of the body in the file
};

Header read_header(const MeshSource& source) {
  Lines lines(source.bytes);
  const auto at = [&](const std::string& detail) {
    source.fail("header line " + std::to_string(lines.number()) + ": " + detail);
  };
  std::string_view line, word;
  if (!lines.next(line) || line != "ply")
    source.fail("not a PLY file: it does not start with 'ply'");
  Header header;
  bool format_seen = false;
  while (true) {
    if (!lines.next(line)) source.fail("the header has no 'end_header'");
    Words words(line);
    if (!words.next(word)) continue;
    if (word == "end_header") break;
    if (word == "comment" || word == "obj_info") continue;
    if (word == "format") {
      std::string_view name, version;
      if (format_seen || !words.next(name) || !words.next(version) || version != "1.0") {
        at("expected one 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
      }
      format_seen = true;
      if (name == "ascii") {
        header.format = Format::kAscii;
      } else if (name == "binary_little_endian") {
        header.format = Format::kBinaryLittleEndian;
      } else if (name == "binary_big_endian") {
        header.format = Format::kBinaryBigEndian;
      } else {
        at("unknown format '" + std::string(name) + "'");
      }
    } else if (word == "element") {
      std::string_view name, count;
      if (!words.next(name) || !words.next(count)) at("expected 'element <name> <count>'");
      const auto n = parse_integer(count);
      if (!n) at("cannot parse element count '" + std::string(count) + "'");
      header.elements.push_back({std::string(name), *n, {}});
    } else if (word == "property") {
      if (header.elements.empty()) at("a property before any element");
      Property property;
      std::string_view type, name;
      if (!words.next(type)) at("expected 'property <type> <name>'");
      if (type == "list") {
        std::string_view count_type;
        if (!words.next(count_type) || !words.next(type)) {
          at("expected 'property list <count type> <item type> <name>'");
        }
        property.list_count_type = parse_type(count_type);
        if (!property.list_count_type || !is_integer(*property.list_count_type)) {
          at("a list count of type '" + std::string(count_type) + "'");
        }
      }
      const auto item = parse_type(type);
      if (!item) at("unknown property type '" + std::string(type) + "'");
      property.type = *item;
      if (!words.next(name)) at("a property without a name");
      property.name = name;
      header.elements.back().properties.push_back(std::move(property));
    } else {
      at("unexpected '" + std::string(line.substr(0, 40)) + "'");
    }
  }
  if (!format_seen) source.fail("the header has no 'format' line");
  header.body = lines.offset();
  return header;
}

/// An element instance ("face 12"), named only when a message needs it: most files have
/// millions and no message.
struct Instance {
  const std::string& element;
  long long index;
  std::string name() const { return element + " " + std::to_string(index); }
};

/// Reads the body's values in order, as doubles, from either ASCII or binary data.
class ValueReader {
 public:
  ValueReader(const MeshSource& source, const Header& header)
      : source_(source),
        ascii_(header.format == Format::kAscii),
        binary_(source.bytes, header.body, header.format == Format::kBinaryBigEndian),
        text_(source.bytes.substr(header.body)) {}

  /// The next value, of the given type; `what` names it if the data ends or is malformed.
  double next(Type type, const Instance& what) {
    if (ascii_) {
      std::string_view word;
      while (!words_.next(word)) {
        std::string_view line;
        if (!text_.next(line)) source_.fail("the data ends in " + what.name());
        words_ = Words(line);
      }
      const auto value = is_integer(type) ? parse_integer_value(word) : parse_real(word);
      if (!value)
        source_.fail("cannot parse '" + std::string(word.substr(0, 40)) + "' in " + what.name());
      return *value;
    }
    switch (type) {
      case Type::kInt8:
        return read<int8_t>(what);
      case Type::kUint8:
        return read<uint8_t>(what);
      case Type::kInt16:
        return read<int16_t>(what);
      case Type::kUint16:
        return read<uint16_t>(what);
      case Type::kInt32:
        return read<int32_t>(what);
      case Type::kUint32:
        return read<uint32_t>(what);
      case Type::kFloat32:
        return read<float>(what);
      case Type::kFloat64:
        return read<double>(what);
    }
    return 0;
  }

  /// Bytes after the header, for the checks of what it claims. ASCII gets one more: its last
  /// value needs no separator after it.
  std::uintmax_t body_bytes() const { return binary_.remaining() + (ascii_ ? 1 : 0); }

 private:
  static std::optional<double> parse_integer_value(std::string_view word) {
    const auto n = parse_integer(word);
    return n ? std::optional<double>(static_cast<double>(*n)) : std::nullopt;
  }
  template <class T>
  double read(const Instance& what) {
    T value{};
    if (!binary_.read(value)) source_.fail("the data ends in " + what.name());
    return static_cast<double>(value);
  }
  const MeshSource& source_;
  bool ascii_;
  ByteReader binary_;  ///< the body as bytes; in ASCII only its size is used
  Lines text_;
  Words words_{std::string_view()};
};

}  // namespace

Faces read_ply(const MeshSource& source, std::vector<std::string>& warnings) {
  const Header header = read_header(source);
  ValueReader values(source, header);
  const bool binary = header.format != Format::kAscii;

  // Every claimed count against the limits and the bytes the body has, before reserving.
  std::uintmax_t left = values.body_bytes();
  for (const Element& e : header.elements) {
    const bool mesh = e.name == "vertex" || e.name == "face";
    const std::uintmax_t each = std::max<std::uintmax_t>(e.min_bytes(binary), 1);
    source.check_claim(e.count, mesh ? (e.name == "vertex" ? "vertices" : "faces") : "elements",
                       e.name == "face" ? limits::kPolygons : limits::kMeshVertices, each, left);
    left -= each * static_cast<std::uintmax_t>(e.count);
  }

  SoupBuilder soup(source, 0);
  bool has_vertices = false;
  for (const Element& e : header.elements) {
    int xyz[3] = {-1, -1, -1};  // property index of x, y, z in a vertex
    int corners = -1;           // property index of a face's vertex list
    for (int p = 0; p < static_cast<int>(e.properties.size()); ++p) {
      const Property& property = e.properties[p];
      for (int c = 0; c < 3; ++c) {
        if (e.name == "vertex" && !property.list_count_type &&
            property.name == std::string(1, "xyz"[c])) {
          xyz[c] = p;
        }
      }
      if (e.name == "face" && property.list_count_type && corners < 0 &&
          (property.name == "vertex_indices" || property.name == "vertex_index")) {
        if (!is_integer(property.type)) source.fail("face vertex indices of a real type");
        corners = p;
      }
    }
    if (e.name == "vertex") {
      if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0) source.fail("the vertices have no x, y and z");
      has_vertices = true;
      soup.reserve(e.count, 0);
    } else if (e.name == "face") {
      if (corners < 0) source.fail("the faces have no list 'vertex_indices'");
      soup.reserve(0, e.count);
    } else if (e.count > 0) {
      warnings.push_back(source.where + ": " + source.file + ": element '" + e.name + "' (" +
                         std::to_string(e.count) + ") is not read");
    }

    for (long long i = 0; i < e.count; ++i) {
      const Instance what{e.name, i};
      Vec3 p;
      for (int k = 0; k < static_cast<int>(e.properties.size()); ++k) {
        const Property& property = e.properties[k];
        if (!property.list_count_type) {
          const double value = values.next(property.type, what);
          for (int c = 0; c < 3; ++c) {
            if (k == xyz[c]) p[c] = value;
          }
          continue;
        }
        const double n = values.next(*property.list_count_type, what);
        if (n < 0) source.fail(what.name() + " has a list of negative length");
        if (k == corners && n > limits::kPolygonVertices) {
          source.fail(what.name() + " has more than " + std::to_string(limits::kPolygonVertices) +
                      " vertices");
        }
        for (long long item = 0; item < static_cast<long long>(n); ++item) {
          const double value = values.next(property.type, what);
          if (k == corners) soup.add_index(static_cast<long long>(value));
        }
      }
      if (e.name == "vertex") soup.add_vertex(p);
      if (e.name == "face") soup.end_face();
    }
  }
  if (!has_vertices) source.fail("the file has no element 'vertex'");
  return soup.take();
}

}  // namespace rad::mesh_formats
