#pragma once
/// The polygon-soup readers behind read_mesh_faces (mesh_reader.h), one file per format
/// (mesh_obj.cpp, mesh_off.cpp, mesh_ply.cpp, mesh_stl.cpp), and what they share: the file's
/// bytes with how to name them in a message, the checks of what a header claims, and the
/// soup they fill.
///
/// They are ours rather than OpenMesh's because a radiosity scene is a polygon soup: every face
/// must come back in file order with its own vertices, and validated one by one
/// (polygon_validation.h), whereas OpenMesh's readers build a half-edge mesh, merging or dropping
/// faces it cannot add. Fuzzing also found an abort (OBJ), a hang (PLY header) and an unbounded
/// reservation (binary OFF) inside them (fuzz/regressions/). These readers check every count
/// and index against the limits (scene/limits.h) and the bytes the file has before they
/// allocate, and parse numbers with std::from_chars (no locale; "nan" and "inf" parse, so that
/// validation can name them).
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "geometry/vec.h"
#include "scene/mesh_reader.h"

namespace rad::mesh_formats {

/// The whole of a model file (a mesh, a material library) within limits::kMeshFileBytes: the
/// bytes recorded in `files` for it, or else read from disk (a regular file only:
/// check_input_file) and recorded there. `what` ("mesh file") and `where` (the scene element)
/// name it in messages.
std::string read_model_file(const std::filesystem::path& file, const std::string& what,
                            const std::string& where, InputFiles* files);

/// The file's extension in lower case (".obj").
std::string lower_extension(const std::filesystem::path& file);

/// Faces as vertex lists, in file order.
using Faces = std::vector<std::vector<Vec3>>;

/// A mesh file's bytes and the names a message gives it.
struct MeshSource {
  std::string_view bytes;
  std::string file;   ///< the path, as in messages: 'scenes/bunny.ply'
  std::string where;  ///< the scene element: "scene.json: objects[0] (bunny.ply)"

  /// Throws InputError "<where>: cannot read mesh file '<file>' (<detail>)".
  [[noreturn]] void fail(const std::string& detail) const;
  /// Throws InputError when a header claims a negative `count` of `what` ("vertices"), more
  /// than `limit`, or more than `available` bytes hold at `min_bytes` each (a short file must
  /// not make a reader reserve memory for billions of elements).
  void check_claim(long long count, const char* what, long long limit, std::uintmax_t min_bytes,
                   std::uintmax_t available) const;
};

/// Vertices and faces by index, resolved to vertex lists at the end. Indices are checked once,
/// in take(), and counted against the limits as they come.
class SoupBuilder {
 public:
  /// `first_index` is what the format calls the first vertex (1 in OBJ, 0 in OFF and PLY), for
  /// messages that quote indices as the file has them.
  SoupBuilder(const MeshSource& source, long long first_index);
  /// Reserves for counts a header claims; call after MeshSource::check_claim.
  void reserve(long long vertices, long long faces);
  void add_vertex(const Vec3& p);
  long long vertex_count() const { return static_cast<long long>(vertices_.size()); }
  /// Adds a vertex index (0-based) to the face being read.
  void add_index(long long index);
  /// Ends the face being read (it may be empty: validation names it).
  void end_face();
  long long face_count() const { return static_cast<long long>(face_ends_.size()); }
  /// The faces, each index resolved; throws naming the first face with an index out of range.
  Faces take();

 private:
  const MeshSource& source_;
  long long first_index_;
  std::vector<Vec3> vertices_;
  std::vector<long long> indices_;  ///< every face's indices, one after another
  std::vector<size_t> face_ends_;   ///< end of each face in indices_
};

/// Lines of a text, split at '\n' with a trailing '\r' dropped, numbered from 1.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  /// The next line, or false at the end of the text.
  bool next(std::string_view& line);
  /// Number of the line next() returned last.
  long long number() const { return number_; }
  /// Offset in the text just past the line next() returned last (its '\n' included).
  size_t offset() const { return at_; }

 private:
  std::string_view text_;
  size_t at_ = 0;
  long long number_ = 0;
};

/// The words of a line, split at spaces, tabs and other ASCII blanks.
class Words {
 public:
  explicit Words(std::string_view line) : line_(line) {}
  /// The next word, or false at the end of the line.
  bool next(std::string_view& word);
  /// What is left of the line, blanks trimmed at both ends: a name that may hold spaces
  /// ("usemtl Wall inner", "newmtl My Material").
  std::string_view rest() const;

 private:
  std::string_view line_;
};

/// A real number ("1", "-2.5e3", "+4", "nan", "inf"), or nothing if the word is not one.
std::optional<double> parse_real(std::string_view word);
/// A decimal integer ("12", "-3", "+4"), or nothing if the word is not one or overflows.
std::optional<long long> parse_integer(std::string_view word);

/// Reads fixed-size numbers from binary data, in little- or big-endian order, checking the
/// bounds of every read.
class ByteReader {
 public:
  ByteReader(std::string_view bytes, size_t offset, bool big_endian)
      : bytes_(bytes), at_(offset), big_endian_(big_endian) {}
  /// Reads a T (an arithmetic type); false when the data ends first.
  template <class T>
  bool read(T& value) {
    if (at_ > bytes_.size() || bytes_.size() - at_ < sizeof(T)) return false;
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, bytes_.data() + at_, sizeof(T));
    if (big_endian_ != kHostBigEndian) {
      for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    }
    std::memcpy(&value, raw, sizeof(T));
    at_ += sizeof(T);
    return true;
  }
  size_t offset() const { return at_; }
  size_t remaining() const { return at_ < bytes_.size() ? bytes_.size() - at_ : 0; }

 private:
  static constexpr bool kHostBigEndian = __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__;
  std::string_view bytes_;
  size_t at_;
  bool big_endian_;
};

/// The format readers. Each throws InputError through source.fail() or check_claim(); `warnings`
/// receive what a reader skips that a user may miss (OBJ lines and curves, PLY elements other
/// than vertex and face). read_obj also stores what the file says of its materials.
Faces read_obj(const MeshSource& source, std::vector<std::string>& warnings,
               MeshMaterials& materials);
Faces read_off(const MeshSource& source);
Faces read_ply(const MeshSource& source, std::vector<std::string>& warnings);
Faces read_stl(const MeshSource& source);

}  // namespace rad::mesh_formats
