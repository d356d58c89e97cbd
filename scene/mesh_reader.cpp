#include "scene/mesh_reader.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <mutex>
#include <sstream>

#include "scene/error.h"
#include "scene/limits.h"

namespace rad {
namespace {

struct DoubleTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
};
using ReadMesh = OpenMesh::PolyMesh_ArrayKernelT<DoubleTraits>;

/// Routes OpenMesh's global log streams into a buffer, so library code prints nothing and the
/// messages become warnings that name the file. The buffer is connected once for the process:
/// OpenMesh's multiplex_streambuf::disconnect never frees what connect allocated (a leak per
/// read that LeakSanitizer reports), and OpenMesh's logging has no other reader here.
class CaptureOpenMeshLog {
 public:
  CaptureOpenMeshLog() : lock_(mutex()) {
    static const bool connected = [] {
      for (auto* s : {&omerr(), &omlog(), &omout()}) {
        s->disconnect(std::cerr);
        s->disconnect(std::cout);
        s->connect(buffer());
      }
      return true;
    }();
    (void)connected;
    buffer().str("");
  }
  std::vector<std::string> lines() {
    for (auto* s : {&omerr(), &omlog(), &omout()}) s->flush();
    std::vector<std::string> out;
    std::istringstream in(buffer().str());
    for (std::string line; std::getline(in, line);) {
      if (!line.empty()) out.push_back(line);
    }
    return out;
  }

 private:
  static std::ostringstream& buffer() {
    static std::ostringstream b;
    return b;
  }
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> lock_;  ///< One reader of the shared buffer at a time
};

std::string lower_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

/// STL is read here rather than by OpenMesh, whose STL reader merges vertices by position and
/// silently drops facets that become degenerate, including those with NaN coordinates. Every
/// facet is returned in file order; validation happens later, per facet.
std::vector<std::vector<Vec3>> read_stl_faces(const std::filesystem::path& file,
                                              const std::string& where) {
  std::ifstream in(file, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::vector<Vec3>> faces;
  // Binary STL: 80-byte header, uint32 count, 50 bytes per facet. The size check, not the
  // "solid" keyword, decides: many binary files start their header with "solid".
  if (bytes.size() >= 84) {
    uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    if (bytes.size() == 84 + 50ull * count) {
      for (uint32_t f = 0; f < count; ++f) {
        const char* facet = bytes.data() + 84 + 50ull * f + 12;  // skip the stored normal
        std::vector<Vec3> vertices;
        for (int v = 0; v < 3; ++v) {
          float xyz[3];
          std::memcpy(xyz, facet + 12 * v, 12);
          vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
        }
        faces.push_back(std::move(vertices));
      }
      return faces;
    }
  }
  std::istringstream text(bytes);
  std::string word;
  if (!(text >> word) || word != "solid") {
    throw InputError(where + ": '" + file.string() + "' is neither binary nor ASCII STL");
  }
  std::vector<Vec3> current;
  for (int line = 0; text >> word; ++line) {
    if (word == "vertex") {
      // strtod, unlike operator>>, parses "nan" and "inf", so validation can name them.
      std::string xyz[3];
      text >> xyz[0] >> xyz[1] >> xyz[2];
      Vec3 p;
      for (int c = 0; c < 3; ++c) {
        char* end = nullptr;
        p[c] = std::strtod(xyz[c].c_str(), &end);
        if (xyz[c].empty() || *end != '\0') {
          throw InputError(where + ": '" + file.string() + "' facet " +
                           std::to_string(faces.size()) + ": cannot parse vertex coordinate '" +
                           xyz[c] + "'");
        }
      }
      current.push_back(p);
    } else if (word == "endloop") {
      faces.push_back(std::move(current));
      current.clear();
    }
  }
  if (faces.empty()) throw InputError(where + ": '" + file.string() + "' has no facets");
  return faces;
}

/// The element counts a PLY or OFF header claims, against what the file can hold (every vertex
/// and face takes at least 2 bytes, in ASCII or binary) and limits::kPolygons: a short file
/// must not make the reader reserve memory for billions of vertices. OBJ has no counts.
void check_claimed_counts(const std::filesystem::path& file, const std::string& where,
                          std::uintmax_t bytes) {
  const std::string ext = lower_extension(file);
  if (ext != ".ply" && ext != ".off") return;
  std::ifstream in(file, std::ios::binary);
  std::string header(4096, '\0');
  in.read(header.data(), static_cast<std::streamsize>(header.size()));
  header.resize(static_cast<size_t>(in.gcount()));
  std::vector<long double> counts;
  const auto number_at = [&](size_t i) {
    while (i < header.size() && (header[i] == ' ' || header[i] == '\t')) ++i;
    long double n = 0;
    for (; i < header.size() && std::isdigit(static_cast<unsigned char>(header[i])); ++i)
      n = 10 * n + (header[i] - '0');
    return n;
  };
  if (ext == ".ply") {
    for (const char* element : {"element vertex", "element face"}) {
      const size_t at = header.find(element);
      if (at != std::string::npos) counts.push_back(number_at(at + std::strlen(element)));
    }
  } else {
    // "OFF" (or "COFF", "NOFF", ...) then the first non-comment line: vertices faces edges.
    std::istringstream lines(header);
    std::string line;
    bool magic = false;
    while (std::getline(lines, line)) {
      if (line.empty() || line[0] == '#') continue;
      if (!magic) {
        magic = true;
        if (line.find("OFF") != std::string::npos &&
            line.find_first_of("0123456789") == std::string::npos)
          continue;
      }
      std::istringstream fields(
          line.substr(line.find("OFF") == std::string::npos ? 0 : line.find("OFF") + 3));
      long double v = 0, f = 0;
      if (fields >> v >> f) counts = {v, f};
      break;
    }
  }
  for (const long double n : counts) {
    if (n < 0) {
      throw InputError(where + ": mesh file '" + file.string() + "' claims a negative count (" +
                       std::to_string(static_cast<long long>(n)) + ")");
    }
    if (n > limits::kPolygons || 2 * n > static_cast<long double>(bytes)) {
      throw InputError(where + ": mesh file '" + file.string() + "' claims " +
                       std::to_string(static_cast<long long>(std::min<long double>(n, 1e18))) +
                       " elements, more than " +
                       (n > limits::kPolygons ? "the limit of " + std::to_string(limits::kPolygons)
                                              : "its " + std::to_string(bytes) + " bytes hold"));
    }
  }
}

}  // namespace

bool is_supported_mesh_extension(const std::filesystem::path& file) {
  const std::string ext = lower_extension(file);
  return ext == ".obj" || ext == ".ply" || ext == ".off" || ext == ".stl";
}

std::vector<std::vector<Vec3>> read_mesh_faces(const std::filesystem::path& file,
                                               const std::string& where,
                                               std::vector<std::string>& warnings) {
  if (!is_supported_mesh_extension(file)) {
    throw InputError(where + ": unsupported mesh format '" + file.extension().string() + "' of '" +
                     file.string() + "' (supported: .obj .ply .off .stl)");
  }
  std::error_code error;
  if (!std::ifstream(file).good() || !std::filesystem::is_regular_file(file, error)) {
    throw InputError(where + ": cannot open mesh file '" + file.string() + "'");
  }
  const std::uintmax_t bytes = std::filesystem::file_size(file, error);
  if (error || bytes > limits::kMeshFileBytes) {
    throw InputError(where + ": mesh file '" + file.string() + "' is larger than the limit of " +
                     std::to_string(limits::kMeshFileBytes >> 20) + " MiB");
  }
  check_claimed_counts(file, where, bytes);
  if (lower_extension(file) == ".stl") return read_stl_faces(file, where);

  ReadMesh mesh;
  bool ok = false;
  std::vector<std::string> log;
  {
    CaptureOpenMeshLog capture;
    OpenMesh::IO::Options options;  // positions only: normals are recomputed from the vertices
    // OpenMesh's readers choose by extension and compare it case-sensitively.
    ok = OpenMesh::IO::read_mesh(mesh, file.string(), options);
    log = capture.lines();
  }
  if (!ok) {
    std::string detail = log.empty() ? "" : " (" + log.front() + ")";
    throw InputError(where + ": cannot read mesh file '" + file.string() + "'" + detail);
  }
  for (const std::string& line : log) {
    // OpenMesh logs "complex edge" for a non-manifold face and then keeps it with duplicated
    // vertices (ImporterT::add_face), which is what a polygon soup wants: not worth a warning.
    if (line.find("complex edge") != std::string::npos) continue;
    // A face OpenMesh could not add (unparsable or non-finite vertex, repeated vertex) would be
    // lost without a trace: that is an error, not a warning. These are the messages of
    // OpenMesh 9's importer and readers that mean a face was dropped; its other remarks (e.g.
    // PLY properties it skips) stay warnings.
    for (const char* lost : {"Face contains invalid vertex index", "Face has equal vertices",
                             "invalid faces, that could not be added"}) {
      if (line.find(lost) != std::string::npos) {
        throw InputError(where + ": cannot read every face of '" + file.string() + "' (" + line +
                         ")");
      }
    }
    warnings.push_back(where + ": " + file.filename().string() + ": " + line);
  }
  if (mesh.n_faces() == 0) {
    std::string detail = log.empty() ? "" : " (" + log.front() + ")";
    throw InputError(where + ": mesh file '" + file.string() + "' has no readable faces" + detail);
  }

  std::vector<std::vector<Vec3>> faces;
  faces.reserve(mesh.n_faces());
  for (const auto face : mesh.faces()) {
    std::vector<Vec3> vertices;
    for (const auto vertex : face.vertices()) {
      const OpenMesh::Vec3d& p = mesh.point(vertex);
      vertices.emplace_back(p[0], p[1], p[2]);
    }
    faces.push_back(std::move(vertices));
  }
  return faces;
}

}  // namespace rad
