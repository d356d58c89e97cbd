#include "viz/vtk_export.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLImageDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>

#include "formats/atomic_file.h"
#include "formats/image_io.h"
#include "formats/patch_mesh_polydata.h"
#include "scene/error.h"
#include "scene/polygon.h"
#include "viz/offscreen_display.h"

namespace rad {
namespace {

template <class Writer, class Data>
void write_xml(const std::filesystem::path& file, Data* data, const std::string& what) {
  AtomicFile out(file);
  vtkNew<Writer> writer;
  writer->SetFileName(out.temp_path().c_str());
  writer->SetInputData(data);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  if (writer->Write() != 1 || writer->GetErrorCode() != 0)
    throw Error(file.string() + ": cannot write " + what);
  out.commit();
}

}  // namespace

void write_octree_vtu(const std::filesystem::path& file, const Octree& octree) {
  const auto& voxels = octree.voxels();
  // Energy per voxel, accumulated from the leaves up (children follow their parents).
  std::vector<double> energy(voxels.size(), 0.0);
  for (size_t v = 0; v < voxels.size(); ++v) {
    for (const int i : voxels[v].items) {
      const OctreeItem& item = octree.items()[i];
      energy[v] +=
          0.5 * newell_vector(item.corners).norm() * item.radiosity.maxCoeff();  // area x B
    }
  }
  for (size_t v = voxels.size(); v-- > 0;) {
    if (voxels[v].is_leaf()) continue;
    for (int c = 0; c < 8; ++c) energy[v] += energy[voxels[v].first_child + c];
  }

  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> bmax, bmax_max, energy_array;
  vtkNew<vtkIntArray> count, level, leaf;
  bmax->SetName("bmax");
  bmax->SetNumberOfComponents(3);
  bmax_max->SetName("bmax_max");
  energy_array->SetName("energy");
  count->SetName("patch_count");
  level->SetName("level");
  leaf->SetName("leaf");
  for (size_t v = 0; v < voxels.size(); ++v) {
    const Voxel& voxel = voxels[v];
    if (voxel.item_count == 0) continue;
    const Vec3 lo = voxel.cell.min(), hi = voxel.cell.max();
    // VTK_HEXAHEDRON order: the bottom face counter-clockwise, then the top face above it.
    vtkIdType ids[8];
    const double corners[8][3] = {{lo.x(), lo.y(), lo.z()}, {hi.x(), lo.y(), lo.z()},
                                  {hi.x(), hi.y(), lo.z()}, {lo.x(), hi.y(), lo.z()},
                                  {lo.x(), lo.y(), hi.z()}, {hi.x(), lo.y(), hi.z()},
                                  {hi.x(), hi.y(), hi.z()}, {lo.x(), hi.y(), hi.z()}};
    for (int k = 0; k < 8; ++k) ids[k] = points->InsertNextPoint(corners[k]);
    grid->InsertNextCell(VTK_HEXAHEDRON, 8, ids);
    bmax->InsertNextTuple3(voxel.bmax.x(), voxel.bmax.y(), voxel.bmax.z());
    bmax_max->InsertNextValue(voxel.bmax.maxCoeff());
    energy_array->InsertNextValue(energy[v]);
    count->InsertNextValue(voxel.item_count);
    level->InsertNextValue(voxel.level);
    leaf->InsertNextValue(voxel.is_leaf() ? 1 : 0);
  }
  grid->SetPoints(points);
  for (vtkAbstractArray* a :
       std::initializer_list<vtkAbstractArray*>{bmax, bmax_max, energy_array, count, level, leaf}) {
    grid->GetCellData()->AddArray(a);
  }
  grid->GetCellData()->SetActiveScalars("bmax_max");
  write_xml<vtkXMLUnstructuredGridWriter>(file, grid.Get(), "the octree");
}

void write_pixel_image_vti(const std::filesystem::path& file, int width, int height,
                           const std::map<std::string, std::vector<float>>& arrays) {
  vtkNew<vtkImageData> image;
  image->SetDimensions(width, height, 1);
  for (const auto& [name, values] : arrays) {
    if (values.size() != static_cast<size_t>(width) * height) {
      throw Error(file.string() + ": array " + name + " has " + std::to_string(values.size()) +
                  " values for " + std::to_string(width) + "x" + std::to_string(height) +
                  " pixels");
    }
    vtkNew<vtkFloatArray> a;
    a->SetName(name.c_str());
    a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        // VTK's row 0 is the bottom row.
        a->SetValue(static_cast<vtkIdType>(height - 1 - y) * width + x,
                    values[static_cast<size_t>(y) * width + x]);
      }
    }
    image->GetPointData()->AddArray(a);
  }
  write_xml<vtkXMLImageDataWriter>(file, image.Get(), "the pixel image");
}

void write_patch_mesh_png(const std::filesystem::path& file, const Solution& solution,
                          const Scene& scene, const CameraSpec& camera,
                          std::optional<double> given_exposure) {
  ensure_display();
  const vtkSmartPointer<vtkPolyData> mesh = patch_mesh_polydata(solution, scene);
  // Colours are the radiosities tone-mapped as the PNG previews are: what is seen is B itself.
  vtkDataArray* radiosity = mesh->GetCellData()->GetArray("radiosity");
  double exposure = 0;
  if (given_exposure) {
    exposure = *given_exposure;
  } else {
    std::vector<double> brightest;
    for (vtkIdType i = 0; i < mesh->GetNumberOfCells(); ++i) {
      const double* b = radiosity->GetTuple3(i);
      brightest.push_back(std::max({b[0], b[1], b[2]}));
    }
    exposure = auto_exposure(std::move(brightest));
  }
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName("colour");
  colours->SetNumberOfComponents(3);
  for (vtkIdType i = 0; i < mesh->GetNumberOfCells(); ++i) {
    const double* b = radiosity->GetTuple3(i);
    colours->InsertNextTuple3(to_srgb8(b[0], exposure), to_srgb8(b[1], exposure),
                              to_srgb8(b[2], exposure));
  }
  mesh->GetCellData()->AddArray(colours);

  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(mesh);
  mapper->SetScalarModeToUseCellFieldData();
  mapper->SelectColorArray("colour");
  mapper->SetColorModeToDirectScalars();
  mapper->ScalarVisibilityOn();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkProperty* property = actor->GetProperty();
  property->LightingOff();  // flat: the colour is the radiosity, not a shading of it
  property->EdgeVisibilityOn();
  property->SetEdgeColor(0.1, 0.1, 0.1);
  property->SetLineWidth(1);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0, 0, 0);
  vtkCamera* view = renderer->GetActiveCamera();
  view->SetPosition(camera.eye.x(), camera.eye.y(), camera.eye.z());
  view->SetFocalPoint(camera.look_at.x(), camera.look_at.y(), camera.look_at.z());
  view->SetViewUp(camera.up.x(), camera.up.y(), camera.up.z());
  view->SetViewAngle(camera.fov_deg);  // vertical, as the scene camera's
  renderer->ResetCameraClippingRange();

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->AddRenderer(renderer);
  window->SetSize(camera.width, camera.height);
  window->SetMultiSamples(0);
  write_window_png(file, window);
}

}  // namespace rad
