// VTK exports read back with VTK's own readers: the octree (.vtu), per-pixel statistics (.vti),
// the patch mesh (.vtp) and its picture (PNG): cell counts, array names, values that can be
// computed independently (energy from the faces, the pixel orientation).
#include "viz/vtk_export.h"

#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <filesystem>

#include "formats/solution_io.h"
#include "localpass/local_pass.h"
#include "radiosity/solution_faces.h"
#include "radiosity/solver.h"
#include "scene/error.h"
#include "scene/polygon_faces.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "tests/scratch_dir.h"
#include "tests/viz/png_inspect.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

struct Solved {
  Scene scene;
  Solution solution;
};
const Solved& light_over_floor() {
  static const Solved s = [] {
    Solved out;
    out.scene = load_scene(fs::path(RAD_SOURCE_DIR) / "data/light-over-floor/scene.json");
    SolverSettings settings;
    settings.patch_size = 0.2;
    settings.unshot_fraction = 1e-2;
    out.solution = solve(RayCaster(out.scene), settings);
    return out;
  }();
  return s;
}

TEST(VtkExport, OctreeReadsBackAsHexahedraWithItsArrays) {
  const fs::path dir = test::scratch_dir("viz_octree");
  const Solved& s = light_over_floor();
  const std::vector<EmittingFace> faces = faces_from_solution(s.scene, s.solution);
  const Octree octree(octree_items(faces));
  write_octree_vtu(dir / "octree.vtu", octree);

  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName((dir / "octree.vtu").c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  long non_empty = 0;
  for (const Voxel& v : octree.voxels()) non_empty += v.item_count > 0;
  ASSERT_EQ(grid->GetNumberOfCells(), non_empty);
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
    ASSERT_EQ(grid->GetCellType(c), VTK_HEXAHEDRON);
  vtkCellData* data = grid->GetCellData();
  for (const char* name : {"bmax", "bmax_max", "patch_count", "energy", "level", "leaf"}) {
    ASSERT_NE(data->GetArray(name), nullptr) << name;
  }
  EXPECT_EQ(data->GetArray("bmax")->GetNumberOfComponents(), 3);

  // Leaves: as many as the octree's, holding every item once; their energy adds up to the
  // faces' power, computed here from the faces (area by the shoelace formula in 3D).
  double leaves = 0, items = 0, energy = 0, power = 0;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c) {
    if (data->GetArray("leaf")->GetTuple1(c) != 1) continue;
    ++leaves;
    items += data->GetArray("patch_count")->GetTuple1(c);
    energy += data->GetArray("energy")->GetTuple1(c);
  }
  for (const EmittingFace& f : faces) {
    Vec3 twice_area = Vec3::Zero();
    for (size_t i = 0; i < f.vertices.size(); ++i)
      twice_area += f.vertices[i].cross(f.vertices[(i + 1) % f.vertices.size()]);
    power += 0.5 * twice_area.norm() * f.exitance.maxCoeff();
  }
  EXPECT_EQ(leaves, static_cast<double>(octree.leaves().size()));
  EXPECT_EQ(items, static_cast<double>(faces.size()));
  EXPECT_NEAR(energy, power, 1e-9 * power);
  // The root (the first cell) holds everything, and its energy is the leaves' sum.
  EXPECT_EQ(data->GetArray("patch_count")->GetTuple1(0), static_cast<double>(faces.size()));
  EXPECT_NEAR(data->GetArray("energy")->GetTuple1(0), power, 1e-9 * power);
}

TEST(VtkExport, PixelImageReadsBackRightSideUp) {
  const fs::path dir = test::scratch_dir("viz_pixels");
  // 3 x 2 pixels, rows from the top: the top-left pixel is 1.
  write_pixel_image_vti(dir / "p.vti", 3, 2,
                        {{"projected", {1, 2, 3, 4, 5, 6}}, {"bound", {0, 0, 0, 0, 0, 0.5}}});
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName((dir / "p.vti").c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(dims[0], 3);
  EXPECT_EQ(dims[1], 2);
  vtkDataArray* projected = image->GetPointData()->GetArray("projected");
  ASSERT_NE(projected, nullptr);
  ASSERT_NE(image->GetPointData()->GetArray("bound"), nullptr);
  // VTK's y grows upwards: the top row of the picture is y = 1.
  const int top_left[3] = {0, 1, 0}, bottom_right[3] = {2, 0, 0};
  EXPECT_EQ(projected->GetTuple1(image->ComputePointId(const_cast<int*>(top_left))), 1.0);
  EXPECT_EQ(projected->GetTuple1(image->ComputePointId(const_cast<int*>(bottom_right))), 6.0);
  EXPECT_THROW(write_pixel_image_vti(dir / "bad.vti", 3, 2, {{"short", {1, 2}}}), Error);
}

TEST(VtkExport, PatchMeshFileAndPictureFromTheSceneCamera) {
  const fs::path dir = test::scratch_dir("viz_mesh");
  const Solved& s = light_over_floor();
  write_solution(dir / "patch_mesh.vtp", s.solution, s.scene);
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((dir / "patch_mesh.vtp").c_str());
  reader->Update();
  EXPECT_EQ(reader->GetOutput()->GetNumberOfCells(),
            static_cast<vtkIdType>(s.solution.leaves().size()));
  for (const char* name : {"radiosity", "emission", "reflectance", "level"}) {
    EXPECT_NE(reader->GetOutput()->GetCellData()->GetArray(name), nullptr) << name;
  }

  CameraSpec camera = *s.scene.camera;
  camera.width = 160;
  camera.height = 120;
  write_patch_mesh_png(dir / "patch_mesh.png", s.solution, s.scene, camera);
  const test::PngSummary png = test::inspect_png(dir / "patch_mesh.png");
  EXPECT_EQ(png.width, 160);
  EXPECT_EQ(png.height, 120);
  EXPECT_GT(png.colours, 10u);  // lit elements of several radiosities, edges, background
}

}  // namespace
}  // namespace rad
