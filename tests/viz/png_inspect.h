#pragma once
/// Reading a PNG back with VTK's reader, for tests of pictures: its size and how many distinct
/// colours it has.
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include <filesystem>
#include <set>
#include <tuple>

namespace rad::test {

struct PngSummary {
  int width = 0, height = 0;
  size_t colours = 0;  ///< distinct RGB triples
};

inline PngSummary inspect_png(const std::filesystem::path& file) {
  PngSummary s;
  vtkNew<vtkPNGReader> reader;
  if (!reader->CanReadFile(file.c_str())) return s;
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  s.width = dims[0];
  s.height = dims[1];
  const int components = image->GetNumberOfScalarComponents();
  std::set<std::tuple<int, int, int>> colours;
  for (int y = 0; y < dims[1]; ++y) {
    for (int x = 0; x < dims[0]; ++x) {
      const auto* p = static_cast<unsigned char*>(image->GetScalarPointer(x, y, 0));
      colours.insert({p[0], components > 1 ? p[1] : p[0], components > 2 ? p[2] : p[0]});
    }
  }
  s.colours = colours.size();
  return s;
}

}  // namespace rad::test
