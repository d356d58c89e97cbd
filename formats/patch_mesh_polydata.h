#pragma once
/// Inside viz: the solution's patch mesh as VTK polydata, shared by the solution file and the
/// pictures (solution_io.cpp builds it; VTK types stay out of the public headers).
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include "radiosity/solution.h"
#include "scene/scene.h"

namespace rad {

/// The cells and the cell and point data of the solution file (solution_io.h), without its
/// field data.
vtkSmartPointer<vtkPolyData> patch_mesh_polydata(const Solution& solution, const Scene& scene);

}  // namespace rad
