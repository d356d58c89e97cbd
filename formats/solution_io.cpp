#include "formats/solution_io.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "formats/atomic_file.h"
#include "formats/patch_mesh_polydata.h"
#include "formats/vtk_messages.h"
#include "formats/vtp_guard.h"
#include "radiosity/mesher.h"
#include "radiosity/patch_mesh.h"
#include "scene/error.h"
#include "scene/input_files.h"

// JSON for Eigen's RGB triples, and field lists for the settings and statistics: one list
// serves both writing and reading.
namespace nlohmann {
template <>
struct adl_serializer<rad::Rgb> {
  static void to_json(json& j, const rad::Rgb& v) { j = {v.x(), v.y(), v.z()}; }
  static void from_json(const json& j, rad::Rgb& v) {
    v = {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()};
  }
};
}  // namespace nlohmann

namespace rad {

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(SolverSettings, patch_size, element_levels, refine_threshold,
                                   refine_passes, min_element_size, unshot_fraction, max_shots,
                                   visibility_samples, seed)
// Not the seconds: the file is byte-identical from run to run and for any thread count.
// With defaults: a file written before "redirected" existed reads it as 0, one before
// "error_bound" as -1 (not known).
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(SolveStats, shots, patches, elements, refined,
                                                emitted, absorbed, escaped, unshot, redirected,
                                                unshot_fraction, converged, error_bound)

namespace {

using Json = nlohmann::json;

vtkSmartPointer<vtkDoubleArray> doubles(const char* name, int components) {
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(components);
  return a;
}
vtkSmartPointer<vtkIntArray> ints(const char* name) {
  auto a = vtkSmartPointer<vtkIntArray>::New();
  a->SetName(name);
  return a;
}
void add_string(vtkFieldData* field, const char* name, const std::string& value) {
  vtkNew<vtkStringArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  field->AddArray(a);
}
void add_rgb(vtkDoubleArray* a, const Rgb& v) { a->InsertNextTuple3(v.x(), v.y(), v.z()); }

/// Corners of a list of polygons as (count array, flat xyz array).
void add_corners(vtkFieldData* field, const char* count_name, const char* xyz_name,
                 const std::vector<const std::vector<Vec3>*>& polygons) {
  auto counts = ints(count_name);
  auto xyz = doubles(xyz_name, 3);
  for (const auto* corners : polygons) {
    counts->InsertNextValue(static_cast<int>(corners->size()));
    for (const Vec3& c : *corners) xyz->InsertNextTuple3(c.x(), c.y(), c.z());
  }
  field->AddArray(counts);
  field->AddArray(xyz);
}

}  // namespace

namespace {

/// The patch mesh with its cell and point data, and the element behind each cell.
struct PatchMeshData {
  vtkSmartPointer<vtkPolyData> poly;
  std::vector<int> cell_elements;
};

PatchMeshData build_patch_mesh(const Solution& solution, const Scene& scene) {
  const ElementMesh mesh(solution, scene.tolerance().pad);
  auto poly = vtkSmartPointer<vtkPolyData>::New();

  // Points (double) and cells.
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (const auto v : mesh.mesh().vertices()) {
    const auto& p = mesh.mesh().point(v);
    points->InsertNextPoint(p[0], p[1], p[2]);
  }
  vtkNew<vtkCellArray> cells;
  for (int f = 0; f < mesh.face_count(); ++f) {
    const std::vector<int> ids = mesh.face_vertices(f);
    cells->InsertNextCell(static_cast<vtkIdType>(ids.size()));
    for (const int id : ids) cells->InsertCellPoint(id);
  }
  poly->SetPoints(points);
  poly->SetPolys(cells);

  // Cell data: one tuple per leaf element.
  auto radiosity = doubles("radiosity", 3), emission = doubles("emission", 3);
  auto reflectance = doubles("reflectance", 3), area = doubles("area", 1);
  auto parent = ints("parent_polygon"), patch = ints("patch"), level = ints("level");
  std::vector<Rgb> face_rho;
  std::vector<int> cell_elements;
  for (int f = 0; f < mesh.face_count(); ++f) {
    const Element& e = solution.elements[mesh.element(f)];
    const Material& m = scene.materials[scene.polygons[e.polygon].material];
    add_rgb(radiosity, e.radiosity);
    add_rgb(emission, m.emission);
    add_rgb(reflectance, m.reflectance);
    area->InsertNextValue(e.area);
    parent->InsertNextValue(e.polygon);
    patch->InsertNextValue(e.patch);
    level->InsertNextValue(e.level);
    face_rho.push_back(m.reflectance);
    cell_elements.push_back(mesh.element(f));
  }
  for (auto* a : std::initializer_list<vtkAbstractArray*>{radiosity, emission, reflectance, area,
                                                          parent, patch, level}) {
    poly->GetCellData()->AddArray(a);
  }
  poly->GetCellData()->SetActiveScalars("radiosity");

  // Point data: the Gouraud vertex values (no ambient), for smooth display in ParaView.
  auto vertex_radiosity = doubles("vertex_radiosity", 3);
  for (const Rgb& v : mesh.vertex_radiosity(solution, face_rho, false))
    add_rgb(vertex_radiosity, v);
  poly->GetPointData()->AddArray(vertex_radiosity);
  return {poly, std::move(cell_elements)};
}

}  // namespace

vtkSmartPointer<vtkPolyData> patch_mesh_polydata(const Solution& solution, const Scene& scene) {
  return build_patch_mesh(solution, scene).poly;
}

void write_solution(const std::filesystem::path& file, const Solution& solution,
                    const Scene& scene) {
  const PatchMeshData mesh = build_patch_mesh(solution, scene);
  vtkPolyData* poly = mesh.poly;
  std::vector<const std::vector<Vec3>*> element_corners;
  for (const int e : mesh.cell_elements) element_corners.push_back(&solution.elements[e].corners);
  // Field data: everything else needed to use the solution without solving again.
  vtkFieldData* field = poly->GetFieldData();
  add_string(field, "scene_path", solution.scene_path);
  add_string(field, "scene_fingerprint", solution.scene_fingerprint);
  add_string(field, "settings", Json(solution.settings).dump());
  add_string(field, "stats", Json(solution.stats).dump());
  auto ambient = doubles("ambient", 3);
  add_rgb(ambient, solution.ambient);
  field->AddArray(ambient);
  std::vector<const std::vector<Vec3>*> patch_corners;
  auto patch_polygon = ints("patch_polygon");
  auto patch_radiosity = doubles("patch_radiosity", 3), patch_unshot = doubles("patch_unshot", 3);
  auto patch_normal = doubles("patch_normal", 3);
  for (const Patch& p : solution.patches) {
    patch_corners.push_back(&p.corners);
    patch_polygon->InsertNextValue(p.polygon);
    add_rgb(patch_normal, p.normal);
    add_rgb(patch_radiosity, p.radiosity);
    add_rgb(patch_unshot, p.unshot);
  }
  add_corners(field, "patch_corner_count", "patch_corners", patch_corners);
  add_corners(field, "element_corner_count", "element_corners", element_corners);
  field->AddArray(patch_polygon);
  field->AddArray(patch_radiosity);
  field->AddArray(patch_unshot);
  field->AddArray(patch_normal);

  AtomicFile out(file);
  capture_vtk_messages();
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetFileName(out.temp_path().c_str());
  writer->SetInputData(poly);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw binary: doubles are stored bit for bit
  if (writer->Write() != 1 || writer->GetErrorCode() != 0) {
    throw Error(file.string() + ": cannot write the solution file");
  }
  out.commit();
}

namespace {

class FieldReader {
 public:
  FieldReader(vtkPolyData* poly, std::string file) : poly_(poly), file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& what) const { throw InputError(file_ + ": " + what); }

  vtkDataArray* field(const char* name, int components) const {
    return check(poly_->GetFieldData()->GetArray(name), name, components, "field");
  }
  vtkDataArray* cell(const char* name, int components) const {
    return check(poly_->GetCellData()->GetArray(name), name, components, "cell");
  }
  std::string string(const char* name) const {
    auto* a = vtkStringArray::SafeDownCast(poly_->GetFieldData()->GetAbstractArray(name));
    if (!a || a->GetNumberOfValues() != 1)
      fail(std::string("missing field data string \"") + name + "\"");
    return a->GetValue(0);
  }
  Json json(const char* name) const {
    try {
      return Json::parse(string(name));
    } catch (const Json::exception& e) {
      fail(std::string("field data \"") + name + "\" is not valid JSON: " + e.what());
    }
  }
  /// Polygons stored by add_corners.
  std::vector<std::vector<Vec3>> corners(const char* count_name, const char* xyz_name) const {
    vtkDataArray* counts = field(count_name, 1);
    vtkDataArray* xyz = field(xyz_name, 3);
    std::vector<std::vector<Vec3>> out;
    vtkIdType next = 0;
    for (vtkIdType i = 0; i < counts->GetNumberOfTuples(); ++i) {
      const auto what = std::string("\"") + count_name + "\"[" + std::to_string(i) + "]";
      const int n =
          index(counts, i, static_cast<double>(xyz->GetNumberOfTuples() - next) + 1, what);
      if (n < 3) fail(what + ": fewer than 3 corners");
      std::vector<Vec3> polygon;
      for (int k = 0; k < n; ++k, ++next) polygon.push_back(finite(xyz, next, xyz_name));
      out.push_back(std::move(polygon));
    }
    return out;
  }
  /// Value i of a one-component array as an index in [0, end), or fail naming `what`: a file's
  /// NaN or 1e300 must not reach a cast to int.
  int index(vtkDataArray* a, vtkIdType i, double end, const std::string& what) const {
    const double v = a->GetTuple1(i);
    if (!(v >= 0 && v < end && v < 2147483647.0) || v != std::floor(v)) {
      fail(what + " = " + std::to_string(v) + " is not an index below " +
           std::to_string(static_cast<long long>(std::min(end, 2147483647.0))));
    }
    return static_cast<int>(v);
  }
  /// Tuple i of a three-component array, or fail when it is not finite.
  Vec3 finite(vtkDataArray* a, vtkIdType i, const char* name) const {
    double v[3];
    a->GetTuple(i, v);
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) {
      fail(std::string("\"") + name + "\"[" + std::to_string(i) + "] is not finite");
    }
    return {v[0], v[1], v[2]};
  }

 private:
  vtkDataArray* check(vtkDataArray* a, const char* name, int components, const char* kind) const {
    if (!a) fail(std::string("missing ") + kind + " data array \"" + name + "\"");
    if (a->GetNumberOfComponents() != components) {
      fail(std::string(kind) + " data array \"" + name + "\" has " +
           std::to_string(a->GetNumberOfComponents()) + " components, expected " +
           std::to_string(components));
    }
    return a;
  }
  vtkPolyData* poly_;
  std::string file_;
};

}  // namespace

Solution read_solution(const std::filesystem::path& file) {
  check_input_file(file, "solution file");
  capture_vtk_messages();
  vtkNew<vtkXMLPolyDataReader> reader;
  if (!reader->CanReadFile(file.c_str())) {
    throw InputError(file.string() + ": not a VTK XML PolyData (.vtp) file");
  }
  check_solution_structure(file);
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  const FieldReader in(poly, file.string());
  if (reader->GetErrorCode() != 0 || !poly || !vtk_message().empty()) {
    const std::string why = vtk_message();
    in.fail("cannot read the solution file" + (why.empty() ? "" : " (" + why + ")"));
  }

  Solution s;
  s.scene_path = in.string("scene_path");
  s.scene_fingerprint = in.string("scene_fingerprint");
  try {
    s.settings = in.json("settings").get<SolverSettings>();
    s.stats = in.json("stats").get<SolveStats>();
  } catch (const Json::exception& e) {
    in.fail(std::string("malformed settings or stats: ") + e.what());
  }
  vtkDataArray* ambient = in.field("ambient", 3);
  if (ambient->GetNumberOfTuples() != 1) in.fail("\"ambient\" is not one RGB triple");
  s.ambient = in.finite(ambient, 0, "ambient");

  // Patches.
  const auto patch_corners = in.corners("patch_corner_count", "patch_corners");
  vtkDataArray* patch_polygon = in.field("patch_polygon", 1);
  vtkDataArray* patch_radiosity = in.field("patch_radiosity", 3);
  vtkDataArray* patch_unshot = in.field("patch_unshot", 3);
  vtkDataArray* patch_normal = in.field("patch_normal", 3);
  const vtkIdType patch_count = static_cast<vtkIdType>(patch_corners.size());
  if (patch_polygon->GetNumberOfTuples() != patch_count ||
      patch_radiosity->GetNumberOfTuples() != patch_count ||
      patch_unshot->GetNumberOfTuples() != patch_count ||
      patch_normal->GetNumberOfTuples() != patch_count) {
    in.fail("patch arrays disagree in length");
  }
  for (vtkIdType i = 0; i < patch_count; ++i) {
    Patch p;
    p.polygon = in.index(patch_polygon, i, 2147483647.0, "\"patch_polygon\"");
    p.corners = patch_corners[i];
    Vec3 centroid;
    element_geometry(p.corners, &p.area, &centroid);
    p.normal = in.finite(patch_normal, i, "patch_normal");
    p.radiosity = in.finite(patch_radiosity, i, "patch_radiosity");
    p.unshot = in.finite(patch_unshot, i, "patch_unshot");
    s.patches.push_back(std::move(p));
  }

  // Leaf elements: one per cell.
  const auto element_corners = in.corners("element_corner_count", "element_corners");
  const vtkIdType cells = poly->GetNumberOfCells();
  vtkDataArray* radiosity = in.cell("radiosity", 3);
  vtkDataArray* parent = in.cell("parent_polygon", 1);
  vtkDataArray* patch = in.cell("patch", 1);
  vtkDataArray* level = in.cell("level", 1);
  if (static_cast<vtkIdType>(element_corners.size()) != cells ||
      radiosity->GetNumberOfTuples() != cells || parent->GetNumberOfTuples() != cells ||
      patch->GetNumberOfTuples() != cells || level->GetNumberOfTuples() != cells) {
    in.fail("element arrays disagree with the number of cells");
  }
  for (vtkIdType i = 0; i < cells; ++i) {
    Element e;
    const std::string cell = "cell " + std::to_string(i);
    e.polygon = in.index(parent, i, 2147483647.0, cell + " parent_polygon");
    e.patch = in.index(patch, i, static_cast<double>(patch_count), cell + " patch");
    e.level = in.index(level, i, 64, cell + " level");
    e.corners = element_corners[i];
    element_geometry(e.corners, &e.area, &e.centroid);
    e.radiosity = in.finite(radiosity, i, "radiosity");
    s.elements.push_back(std::move(e));
  }
  return s;
}

}  // namespace rad
