// The mesh readers (scene/mesh_formats.h): every format's variants against what the file says,
// a seeded round trip through writers of this test's own (independent of the readers), and the
// malformed files each must refuse with one message naming the file and the place.
#include "scene/mesh_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "scene/error.h"

namespace rad {
namespace {

using Faces = std::vector<std::vector<Vec3>>;

const std::filesystem::path kData = RAD_TEST_DATA;

class MeshFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ =
        std::filesystem::temp_directory_path() /
        ("rad_mesh_reader_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(folder_);
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }

  /// Writes `bytes` to a file of that name and reads it.
  Faces read(const std::string& name, const std::string& bytes) {
    const auto file = folder_ / name;
    std::ofstream(file, std::ios::binary) << bytes;
    warnings.clear();
    return read_mesh_faces(file, "scene.json: objects[0] (" + name + ")", warnings);
  }
  /// A file's bytes and the words of the message it must get.
  struct Refused {
    std::string bytes, words;
  };
  /// Each case, written to a file of that name, must be refused naming the file and the words.
  void expect_refused(const std::string& name, const std::vector<Refused>& cases) {
    for (const auto& c : cases) {
      const std::string message = error_of(name, c.bytes);
      EXPECT_NE(message.find("objects[0] (" + name + ")"), std::string::npos) << c.bytes << message;
      EXPECT_NE(message.find(c.words), std::string::npos) << c.bytes << "\n  gave: " << message;
    }
  }
  /// The message read() throws, or "" when it reads.
  std::string error_of(const std::string& name, const std::string& bytes) {
    try {
      read(name, bytes);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  std::filesystem::path folder_;
  std::vector<std::string> warnings;
};

/// The unit square at y = 0, counter-clockwise seen from +y, as the files below write it.
const std::vector<Vec3> kSquare{{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}};

TEST_F(MeshFiles, ObjCornersInEveryFormAndRelativeIndices) {
  const Faces faces =
      read("a.obj",
           "# comment\nmtllib a.mtl\no square\n"
           "v 0 0 0\nv 0 0 1 # trailing comment\nv 1 0 1 1.0\nv +1 0 0 0.5 0.5 0.5\n"
           "vt 0 0\nvn 0 1 0\ng one\nusemtl white\ns off\n"
           "f 1/1/1 2//1 3/1 4\n"
           "fo -4 -3 -2 -1\r\n"
           "f\t1 2\t3\n");
  ASSERT_EQ(faces.size(), 3u);
  EXPECT_EQ(faces[0], kSquare);
  EXPECT_EQ(faces[1], kSquare) << "-1 is the latest vertex";
  EXPECT_EQ(faces[2], std::vector<Vec3>(kSquare.begin(), kSquare.begin() + 3));
  EXPECT_TRUE(warnings.empty());
}

TEST_F(MeshFiles, ObjFaceMayNameAVertexDefinedLater) {
  const Faces faces = read("later.obj", "f 1 2 3\nv 0 0 0\nv 0 0 1\nv 1 0 1\n");
  ASSERT_EQ(faces.size(), 1u);
  EXPECT_EQ(faces[0][2], Vec3(1, 0, 1));
}

TEST_F(MeshFiles, ObjWarnsOnceForGeometryItSkips) {
  read("lines.obj", "v 0 0 0\nv 0 0 1\nv 1 0 1\nl 1 2\nl 2 3\np 1\nf 1 2 3\n");
  ASSERT_EQ(warnings.size(), 2u) << "one for 'l', one for 'p'";
  EXPECT_NE(warnings[0].find("lines.obj"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("'l'"), std::string::npos) << warnings[0];
}

TEST_F(MeshFiles, ObjRefusesWhatItCannotRead) {
  const std::vector<Refused> cases{
      {"v 0 0\nf 1 1 1\n", "line 1: a vertex needs 3 coordinates"},
      {"v 0 zero 0\n", "line 1: cannot parse vertex coordinate 'zero'"},
      {"v 0 0 0\nf 1 0 1\n", "line 2: cannot parse face corner '0'"},
      {"v 0 0 0\nf 1 x 1\n", "cannot parse face corner 'x'"},
      {"v 0 0 0\nf -2 -1 -1\n", "line 2: face corner '-2' reaches before the first vertex"},
      {"v 0 0 0\nv 1 0 0\nf 1 2 3\n", "face 0: vertex index 3 is out of range 1..2"},
      {"f 1 2 3\n", "face 0: vertex index 1 is out of range (the file has no vertices)"},
      {"f 99999999999999999999 1 1\n", "cannot parse face corner"},
      {"# nothing\n", "has no readable faces"},
  };
  expect_refused("bad.obj", cases);
}

TEST_F(MeshFiles, ObjKeepsNonFiniteCoordinatesForValidationToName) {
  const Faces faces = read("nan.obj", "v nan 0 0\nv 0 inf 0\nv 0 0 1e999\nf 1 2 3\n");
  EXPECT_TRUE(std::isnan(faces[0][0].x()));
  EXPECT_TRUE(std::isinf(faces[0][1].y()));
  EXPECT_TRUE(std::isinf(faces[0][2].z()));
  EXPECT_EQ(read("tiny.obj", "v 1e-999 0 0\nv 0 0 1\nv 1 0 1\nf 1 2 3\n")[0][0].x(), 0.0);
}

TEST_F(MeshFiles, OffVariants) {
  // Comments, blank lines, counts on the keyword's line, colours after faces and vertices.
  EXPECT_EQ(read("a.off",
                 "# made by hand\nOFF 4 1 0\n\n0 0 0\n0 0 1 # c\n1 0 1\n1 0 0\n4 0 1 2 3 255 0 0\n")
                .at(0),
            kSquare);
  EXPECT_EQ(read("c.off",
                 "COFF\n4 1 4\n0 0 0 1 1 1 1\n0 0 1 1 1 1 1\n1 0 1 1 1 1 1\n"
                 "1 0 0 1 1 1 1\n4 0 1 2 3\n")
                .at(0),
            kSquare);
  EXPECT_EQ(read("n.off",
                 "NOFF\n4 1 0\n0 0 0 0 1 0\n0 0 1 0 1 0\n1 0 1 0 1 0\n1 0 0 0 1 0\n"
                 "4 0 1 2 3\n")
                .at(0),
            kSquare);
  // Homogeneous coordinates are divided by w.
  EXPECT_EQ(read("h.off", "4OFF\n4 1 0\n0 0 0 2\n0 0 2 2\n4 0 4 4\n0.5 0 0 0.5\n4 0 1 2 3\n").at(0),
            kSquare);
  EXPECT_EQ(read("d.off", "nOFF\n3\n4 1 0\n0 0 0\n0 0 1\n1 0 1\n1 0 0\n4 0 1 2 3\n").at(0),
            kSquare);
}

/// Big-endian bytes of a 32-bit value, as binary OFF stores them.
template <class T>
std::string big_endian(T value) {
  static_assert(sizeof(T) == 4);
  uint32_t bits = 0;
  std::memcpy(&bits, &value, 4);
  std::string out(4, '\0');
  for (int i = 0; i < 4; ++i) out[i] = static_cast<char>(bits >> (24 - 8 * i));
  return out;
}

std::string binary_off_square(int face_colours) {
  std::string bytes = "OFF BINARY\n" + big_endian(4) + big_endian(1) + big_endian(0);
  for (const Vec3& p : kSquare) {
    for (int c = 0; c < 3; ++c) bytes += big_endian(static_cast<float>(p[c]));
  }
  bytes += big_endian(4) + big_endian(0) + big_endian(1) + big_endian(2) + big_endian(3);
  bytes += big_endian(face_colours);
  for (int c = 0; c < face_colours; ++c) bytes += big_endian(0.5f);
  return bytes;
}

TEST_F(MeshFiles, OffBinary) {
  EXPECT_EQ(read("b.off", binary_off_square(0)).at(0), kSquare);
  EXPECT_EQ(read("b3.off", binary_off_square(3)).at(0), kSquare);
  std::string truncated = binary_off_square(0);
  truncated.resize(truncated.size() - 6);
  EXPECT_NE(error_of("t.off", truncated).find("binary data ends in face 0"), std::string::npos);
  // The header's counts must fit in the bytes that follow (the fuzzers' 2 GB reservation).
  std::string claims = "OFF BINARY\n" + big_endian(5'000'000) + big_endian(1) + big_endian(0);
  EXPECT_NE(error_of("c.off", claims).find("claims 5000000 vertices, more than its"),
            std::string::npos)
      << error_of("c.off", claims);
}

TEST_F(MeshFiles, OffRefusesWhatItCannotRead) {
  const std::vector<Refused> cases{
      {"", "the file is empty"},
      {"PLY\n", "line 1: expected the keyword OFF"},
      {"OFF\n", "the header has no vertex and face counts"},
      {"OFF\n3 x 0\n", "line 2: cannot parse header count 'x'"},
      {"OFF\n-3 -1 0\n", "claims a negative count (-3) of vertices"},
      {"OFF\n3000000000 1 0\n0 0 0\n", "claims 3000000000 vertices, more than the limit"},
      {"OFF\n300 1 0\n0 0 0\n", "claims 300 vertices, more than its"},
      {"OFF\n3 1 0\n0 0 0\n0 0 1\n1 0\n3 0 1 2\n", "line 5: vertex 2 has too few coordinates"},
      {"OFF\n3 1 0\n0 0 0\n0 0 1\n1 0 1\n3 0 1 7\n", "face 0: vertex index 7 is out of range 0..2"},
      {"OFF\n3 1 0\n0 0 0\n0 0 1\n1 0 1\n3 0 1\n", "face 0 has fewer than 3 vertex indices"},
      {"OFF\n3 2 0\n0 0 0\n0 0 1\n1 0 1\n3 0 1 2\n", "the file ends at face 1"},
      {"OFF\n3 1 0\n0 0 0\n0 0 1\n1 0 1\n-3 0 1 2\n", "face 0 does not start with its vertex"},
      {"nOFF\n4\n3 1 0\n0 0 0 0\n", "vertices of dimension 4"},
  };
  expect_refused("bad.off", cases);
}

TEST_F(MeshFiles, PlyAsciiWithPropertiesAroundTheOnesRead) {
  // A face property before vertex_indices (OpenMesh 9 could not add this face), CRLF line
  // ends, the new type names, and an element of another kind, skipped with a warning.
  const Faces faces = read("a.ply",
                           "ply\r\nformat ascii 1.0\r\ncomment hi\r\nobj_info none\r\n"
                           "element vertex 4\r\nproperty float32 z\r\nproperty uchar red\r\n"
                           "property double x\r\nproperty list uchar float weights\r\n"
                           "property float y\r\n"
                           "element edge 1\r\nproperty int vertex1\r\nproperty int vertex2\r\n"
                           "element face 1\r\nproperty uchar flag\r\n"
                           "property list uint8 int32 vertex_index\r\nend_header\r\n"
                           "0 7 0 0 0\r\n1 7 0 2 0.5 0.5 0\r\n1 7 1 0 0\r\n0 7 1 1 9 0\r\n"
                           "0 1\r\n"
                           "7 4 0 1 2 3\r\n");
  ASSERT_EQ(faces.size(), 1u);
  EXPECT_EQ(faces[0], kSquare);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("element 'edge' (1) is not read"), std::string::npos) << warnings[0];
  warnings.clear();
  const Faces stored = read_mesh_faces(kData / "meshes/face_property_first.ply", "test", warnings);
  ASSERT_EQ(stored.size(), 1u);
  EXPECT_EQ(stored[0].size(), 4u);
}

/// Bytes of a value in the given byte order.
template <class T>
std::string bytes_of(T value, bool big) {
  std::string out(sizeof(T), '\0');
  std::memcpy(out.data(), &value, sizeof(T));
  if (big != (std::endian::native == std::endian::big)) std::reverse(out.begin(), out.end());
  return out;
}

std::string binary_ply_square(bool big) {
  std::string bytes = std::string("ply\nformat ") +
                      (big ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
                      "property double z\nproperty list uchar float normal\n"
                      "element face 1\nproperty list uint uint vertex_indices\n"
                      "property short flags\nend_header\n";
  for (const Vec3& p : kSquare) {
    for (int c = 0; c < 3; ++c) bytes += bytes_of(p[c], big);
    bytes += bytes_of(uint8_t{1}, big) + bytes_of(1.5f, big);
  }
  bytes += bytes_of(uint32_t{4}, big);
  for (uint32_t i = 0; i < 4; ++i) bytes += bytes_of(i, big);
  bytes += bytes_of(int16_t{-1}, big);
  return bytes;
}

TEST_F(MeshFiles, PlyBinaryOfEitherByteOrder) {
  for (const bool big : {false, true}) {
    const Faces faces = read("b.ply", binary_ply_square(big));
    ASSERT_EQ(faces.size(), 1u) << big;
    EXPECT_EQ(faces[0], kSquare) << big;
  }
  std::string truncated = binary_ply_square(false);
  truncated.resize(truncated.size() - 3);
  EXPECT_NE(error_of("t.ply", truncated).find("the data ends in face 0"), std::string::npos)
      << error_of("t.ply", truncated);
}

TEST_F(MeshFiles, PlyRefusesWhatItCannotRead) {
  const std::string vertex =
      "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string face = "element face 1\nproperty list uchar int vertex_indices\n";
  const std::vector<Refused> cases{
      {"this is not a ply file\n", "not a PLY file"},
      {"ply\nformat ascii 1.0\n" + vertex, "the header has no 'end_header'"},
      {"ply\n" + vertex + "end_header\n0 0 0\n", "the header has no 'format' line"},
      {"ply\nformat ascii 2.0\nend_header\n", "header line 2: expected one 'format"},
      {"ply\nformat cobol 1.0\nend_header\n", "header line 2: unknown format 'cobol'"},
      {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", "a property before any element"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n",
       "unknown property type 'float128'"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\nend_header\n",
       "a list count of type 'float'"},
      {"ply\nformat ascii 1.0\nelement vertex x\nend_header\n", "cannot parse element count 'x'"},
      {"ply\nformat ascii 1.0\nelement vertex -1\nend_header\n", "claims a negative count (-1)"},
      {"ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nend_header\n",
       "claims 4000000000 vertices, more than the limit"},
      {"ply\nformat ascii 1.0\nelement vertex 40\nproperty float x\nend_header\n0\n",
       "claims 40 vertices, more than its"},
      {"ply\nformat ascii 1.0\nwhatever\nend_header\n", "header line 3: unexpected 'whatever'"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n",
       "the vertices have no x, y and z"},
      {"ply\nformat ascii 1.0\n" + vertex +
           "element face 1\nproperty int a\nend_header\n0 0 0\n1\n",
       "the faces have no list 'vertex_indices'"},
      {"ply\nformat ascii 1.0\n" + face + "end_header\n3 0 0 0\n", "no element 'vertex'"},
      {"ply\nformat ascii 1.0\n" + vertex + face + "end_header\n0 0 0\n3 0 0 9\n",
       "face 0: vertex index 9 is out of range 0..0"},
      {"ply\nformat ascii 1.0\n" + vertex + face + "end_header\n0 0 0\n3 0 0\n",
       "the data ends in face 0"},
      {"ply\nformat ascii 1.0\n" + vertex + face + "end_header\n0 0 0\n3 0 0 0.5\n",
       "cannot parse '0.5' in face 0"},
      {"ply\nformat ascii 1.0\n" + vertex + face + "end_header\n0 0 0\n-3 0 0 0\n",
       "face 0 has a list of negative length"},
      {"ply\nformat ascii 1.0\n" + vertex +
           "element face 1\nproperty list uchar float vertex_indices\nend_header\n0 0 0\n3 0 0 0\n",
       "face vertex indices of a real type"},
  };
  expect_refused("bad.ply", cases);
}

TEST_F(MeshFiles, StlBinaryAndAscii) {
  std::string binary(80, ' ');
  binary += bytes_of(uint32_t{1}, false);
  for (int i = 0; i < 3; ++i) binary += bytes_of(0.0f, false);  // normal
  for (int v = 0; v < 3; ++v) {
    for (int c = 0; c < 3; ++c) binary += bytes_of(static_cast<float>(kSquare[v][c]), false);
  }
  binary += bytes_of(uint16_t{0}, false);
  const Faces from_binary = read("b.stl", binary);
  ASSERT_EQ(from_binary.size(), 1u);
  EXPECT_EQ(from_binary[0], std::vector<Vec3>(kSquare.begin(), kSquare.begin() + 3));
  const Faces from_ascii = read("a.stl",
                                "\n solid s\nfacet normal 0 1 0\nouter loop\nvertex 0 0 0\n"
                                "vertex 0 0 1\n vertex 1 0 1\nendloop\nendfacet\nendsolid s\n");
  EXPECT_EQ(from_ascii, from_binary);
  EXPECT_NE(error_of("n.stl", "solid\nvertex 0 zero 0\n")
                .find("facet 0: cannot parse vertex "
                      "coordinate 'zero'"),
            std::string::npos);
  EXPECT_NE(error_of("e.stl", "").find("neither binary nor ASCII STL"), std::string::npos);
}

/// A seeded soup of faces with 3 to 6 vertices at float-representable coordinates (so that every
/// format, binary float ones included, stores them exactly), written by the writers below and
/// read back: the readers must return exactly the faces, in order.
Faces random_soup(std::mt19937& rng, bool triangles_only) {
  std::uniform_int_distribution<int> count(3, triangles_only ? 3 : 6);
  std::uniform_real_distribution<float> coordinate(-1e3f, 1e3f);
  Faces faces(20);
  for (auto& face : faces) {
    face.resize(count(rng));
    for (Vec3& p : face) p = Vec3(coordinate(rng), coordinate(rng), coordinate(rng));
  }
  return faces;
}

/// x y z with every digit a double needs (17), so text formats store the values exactly.
std::string exact(const Vec3& p) {
  std::ostringstream out;
  out.precision(17);
  out << p.x() << ' ' << p.y() << ' ' << p.z();
  return out.str();
}

std::string write_obj(const Faces& faces) {
  std::ostringstream text;
  int n = 0;
  for (const auto& face : faces) {
    for (const Vec3& p : face) text << "v " << exact(p) << '\n';
    text << 'f';
    for (size_t i = 0; i < face.size(); ++i) text << ' ' << ++n;
    text << '\n';
  }
  return text.str();
}

std::string write_off(const Faces& faces) {
  std::ostringstream vertices, polygons;
  int n = 0;
  for (const auto& face : faces) {
    polygons << face.size();
    for (const Vec3& p : face) {
      vertices << exact(p) << '\n';
      polygons << ' ' << n++;
    }
    polygons << '\n';
  }
  return "OFF\n" + std::to_string(n) + " " + std::to_string(faces.size()) + " 0\n" +
         vertices.str() + polygons.str();
}

std::string write_binary_ply(const Faces& faces) {
  std::string vertices, polygons;
  int n = 0;
  for (const auto& face : faces) {
    polygons += bytes_of(static_cast<uint8_t>(face.size()), false);
    for (const Vec3& p : face) {
      for (int c = 0; c < 3; ++c) vertices += bytes_of(static_cast<float>(p[c]), false);
      polygons += bytes_of(n++, false);
    }
  }
  return "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(n) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
         std::to_string(faces.size()) + "\nproperty list uchar int vertex_indices\nend_header\n" +
         vertices + polygons;
}

std::string write_ascii_stl(const Faces& faces) {
  std::ostringstream text;
  text << "solid soup\n";
  for (const auto& face : faces) {
    text << "facet normal 0 0 0\nouter loop\n";
    for (const Vec3& p : face) text << "vertex " << exact(p) << '\n';
    text << "endloop\nendfacet\n";
  }
  text << "endsolid soup\n";
  return text.str();
}

TEST_F(MeshFiles, SeededSoupsRoundTripThroughEveryFormat) {
  std::mt19937 rng(16);
  for (int trial = 0; trial < 20; ++trial) {
    const Faces soup = random_soup(rng, false);
    EXPECT_EQ(read("soup.obj", write_obj(soup)), soup) << "trial " << trial;
    EXPECT_EQ(read("soup.off", write_off(soup)), soup) << "trial " << trial;
    EXPECT_EQ(read("soup.ply", write_binary_ply(soup)), soup) << "trial " << trial;
    const Faces triangles = random_soup(rng, true);
    EXPECT_EQ(read("soup.stl", write_ascii_stl(triangles)), triangles) << "trial " << trial;
  }
}

}  // namespace
}  // namespace rad
