// The readers that pull in large parts of VTK (IOGeometry brings FiltersHybrid, IOImage,
// RenderingCore, and with them libtiff, libjpeg, libpng, libwebp: ~20 ms of dynamic loading
// per run, as much as meshing a 2k-tet sphere). tetmesher loads this module with dlopen only
// when it reads an .stl, .obj or .ply file or a surface stored as a non-polydata dataset.
#include "vtkAbstractPolyDataReader.h"
#include "vtkDataSet.h"
#include "vtkGeometryFilter.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPolyData.h"
#include "vtkSTLReader.h"

#include <cstring>

extern "C"
{
  // A new reader for the extension ".stl", ".obj" or ".ply" (lower case), else null. The
  // caller owns it (Delete()).
  __attribute__((visibility("default"))) vtkAbstractPolyDataReader* tetmesherNewSurfaceReader(
    const char* extension)
  {
    if (std::strcmp(extension, ".stl") == 0)
    {
      vtkSTLReader* reader = vtkSTLReader::New();
      reader->MergingOn();
      return reader;
    }
    if (std::strcmp(extension, ".obj") == 0)
      return vtkOBJReader::New();
    if (std::strcmp(extension, ".ply") == 0)
      return vtkPLYReader::New();
    return nullptr;
  }

  // The surface of a dataset (e.g. a surface stored in a .vtu), as vtkGeometryFilter gives it.
  // The caller owns the result (Delete()).
  __attribute__((visibility("default"))) vtkPolyData* tetmesherSurfaceOf(vtkDataSet* data)
  {
    vtkGeometryFilter* geometry = vtkGeometryFilter::New();
    geometry->SetInputData(data);
    geometry->Update();
    vtkPolyData* surface = vtkPolyData::New();
    surface->ShallowCopy(geometry->GetOutput());
    geometry->Delete();
    return surface;
  }
}
