#include "MeshFiles.h"

#include "GmshFile.h"
#include "MeditFile.h"
#include "MeshExport.h"
#include "MeshReport.h"
#include "ModuleLoading.h"
#include "Report.h"
#include "SolverSurfaceFiles.h"

#include "vtkAbstractPolyDataReader.h"
#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDataSetReader.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnstructuredGrid.h"
#include "vtkUnstructuredGridWriter.h"
#include "vtkXMLGenericDataObjectReader.h"
#include "vtkXMLUnstructuredGridWriter.h"

#include <algorithm>
#include <cstdint>
#include <dlfcn.h>
#include <limits>
#include <sstream>
#include <vector>

namespace tetmesher
{
namespace cli
{
namespace
{

void RunReader(vtkAlgorithm* reader, const std::string& path)
{
  std::string error = RunFilter(reader);
  if (!error.empty())
  {
    Fail(path, "unreadable (" + error + ")");
  }
}

// Runs a writer with its errors caught: Write() returns 1 even when the file could not be
// opened, and VTK would print its errors raw.
bool Write(vtkAlgorithm* writer)
{
  return RunFilter(writer).empty() && writer->GetErrorCode() == 0;
}

// A function of the reader module (SurfaceReaders.cxx), loaded on first use and kept loaded
// (the objects it makes use its code).
void* ReaderModuleSymbol(const std::string& path, const char* name)
{
  static void* module = LoadModule("libtetmesherSurfaceReaders.so");
  void* symbol = module ? dlsym(module, name) : nullptr;
  if (!symbol)
  {
    const char* why = dlerror();
    Fail(path,
      std::string("cannot load the surface readers (libtetmesherSurfaceReaders.so: ") +
        (why ? why : "missing symbol") + ")");
  }
  return symbol;
}

std::string Stem(const std::string& path)
{
  auto dot = path.rfind('.');
  return dot == std::string::npos ? path : path.substr(0, dot);
}

// TetGen: NAME.node ("n dim attrs markers" then "id x y z ...") and NAME.ele
// ("m nodesPerTet attrs" then "id v0 v1 v2 v3 ..."), indices from 0 or 1.
vtkSmartPointer<vtkUnstructuredGrid> ReadTetGen(const std::string& path)
{
  const std::string nodePath = Stem(path) + ".node";
  const std::string elePath = Stem(path) + ".ele";
  SurfaceData nodes;
  const long firstId = ReadTetGenNodeFile(nodePath, nodes);
  RequireReadableFile(elePath);
  const long count = static_cast<long>(nodes.PointCount());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(count);
  for (long i = 0; i < count; ++i)
    points->SetPoint(i, &nodes.points[3 * static_cast<std::size_t>(i)]);
  std::istringstream line;
  TokenFile ele(elePath);
  long tetCount = 0, perTet = 0;
  if (!ele.NextLine(line) || !(line >> tetCount >> perTet) || tetCount < 0 || perTet < 4)
  {
    ele.Fail("expected a header 'tetCount nodesPerTet attributes'");
  }
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(points);
  grid->Allocate(tetCount);
  for (long t = 0; t < tetCount; ++t)
  {
    long id;
    vtkIdType v[4];
    if (!ele.NextLine(line) || !(line >> id >> v[0] >> v[1] >> v[2] >> v[3]))
    {
      ele.Fail("expected tetrahedron " + std::to_string(t) + " as 'id v0 v1 v2 v3'");
    }
    for (auto& vertex : v)
    {
      vertex -= firstId;
      if (vertex < 0 || vertex >= count)
      {
        ele.Fail("vertex index out of range (the .node file has " + std::to_string(count) +
          " points starting at " + std::to_string(firstId) + ")");
      }
    }
    grid->InsertNextCell(VTK_TETRA, 4, v);
  }
  return grid;
}

// A grid of VTK_TETRA cells: xyz per point, 4 point ids (from 0) per tet.
vtkSmartPointer<vtkUnstructuredGrid> TetGrid(const std::vector<double>& xyz,
  const std::vector<std::int64_t>& tets)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  const auto pointCount = static_cast<vtkIdType>(xyz.size() / 3);
  points->SetNumberOfPoints(pointCount);
  for (vtkIdType i = 0; i < pointCount; ++i)
    points->SetPoint(i, &xyz[static_cast<std::size_t>(3 * i)]);
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(points);
  const std::size_t tetCount = tets.size() / 4;
  grid->Allocate(static_cast<vtkIdType>(tetCount));
  for (std::size_t t = 0; t < tetCount; ++t)
  {
    vtkIdType v[4];
    for (int k = 0; k < 4; ++k)
      v[k] = static_cast<vtkIdType>(tets[4 * t + static_cast<std::size_t>(k)]);
    grid->InsertNextCell(VTK_TETRA, 4, v);
  }
  return grid;
}

// Gmsh ASCII .msh, format 2.2 and 4.1: nodes and 4-node tetrahedra (element type 4);
// other elements (triangles, lines, points) are skipped.
vtkSmartPointer<vtkUnstructuredGrid> ReadGmsh(const std::string& path)
{
  const GmshMesh mesh =
    ReadGmshMesh(path, [](long type, std::string&) { return type == 4 ? 4 : 0; });
  return TetGrid(mesh.points, mesh.nodes);
}

// Medit ASCII .mesh: vertices and tetrahedra (the Tetrahedra section); the rest is skipped.
vtkSmartPointer<vtkUnstructuredGrid> ReadMedit(const std::string& path)
{
  const MeditMesh mesh = ReadMeditMesh(path);
  if (mesh.tetrahedra.empty())
    Fail(path, "no tetrahedra (a Tetrahedra section with first-order tetrahedra)");
  return TetGrid(mesh.points, mesh.tetrahedra);
}

// A surface of the lean path's readers as vtkPolyData.
vtkSmartPointer<vtkPolyData> PolyDataOf(const SurfaceData& data)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(data.PointCount());
  for (vtkIdType i = 0; i < data.PointCount(); ++i)
    points->SetPoint(i, &data.points[static_cast<std::size_t>(3 * i)]);
  vtkNew<vtkCellArray> polys;
  std::vector<vtkIdType> ids;
  for (vtkIdType f = 0; f < data.PolygonCount(); ++f)
  {
    ids.assign(data.polygonPoints.begin() + data.polygonOffsets[static_cast<std::size_t>(f)],
      data.polygonPoints.begin() + data.polygonOffsets[static_cast<std::size_t>(f + 1)]);
    polys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  }
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  surface->SetPoints(points);
  surface->SetPolys(polys);
  return surface;
}

} // namespace

vtkSmartPointer<vtkDataSet> ReadVolumeMesh(const std::string& path)
{
  const std::string ext = LowerExtension(path);
  if (ext == ".node" || ext == ".ele")
  {
    return ReadTetGen(path);
  }
  RequireReadableFile(path);
  if (ext == ".msh")
  {
    return ReadGmsh(path);
  }
  if (ext == ".mesh")
  {
    return ReadMedit(path);
  }
  if (ext == ".vtu" || ext == ".vtp" || ext == ".vts" || ext == ".vtr" || ext == ".vti")
  {
    vtkNew<vtkXMLGenericDataObjectReader> reader;
    reader->SetFileName(path.c_str());
    RunReader(reader, path);
    auto data = vtkDataSet::SafeDownCast(reader->GetOutputDataObject(0));
    if (!data)
      Fail(path, "does not hold a dataset");
    return data;
  }
  if (ext == ".vtk")
  {
    vtkNew<vtkDataSetReader> reader;
    reader->SetFileName(path.c_str());
    RunReader(reader, path);
    auto data = vtkDataSet::SafeDownCast(reader->GetOutputDataObject(0));
    if (!data)
      Fail(path, "does not hold a dataset");
    return data;
  }
  Fail(path, "unknown file type '" + ext + "' (use .vtu, .vtk, .node/.ele, .msh or .mesh)");
}

vtkSmartPointer<vtkPolyData> ReadSurface(const std::string& path, SurfaceData* lists)
{
  const std::string ext = LowerExtension(path);
  RequireReadableFile(path);
  vtkSmartPointer<vtkPolyData> surface;
  if (ext == ".off")
  {
    return PolyDataOf(ReadOff(path));
  }
  if (IsTetGenSurfaceExtension(ext))
  {
    const SurfaceData data = ReadTetGenSurface(path);
    if (lists)
    {
      lists->holePoints = data.holePoints;
      lists->regionPoints = data.regionPoints;
      lists->regionMaxSizes = data.regionMaxSizes;
    }
    return PolyDataOf(data);
  }
  if (ext == ".msh")
  {
    return PolyDataOf(ReadGmshSurface(path));
  }
  if (ext == ".mesh")
  {
    return PolyDataOf(ReadMeditSurface(path));
  }
  if (ext == ".stl" || ext == ".obj" || ext == ".ply")
  {
    using NewReader = vtkAbstractPolyDataReader* (*)(const char*);
    auto newReader =
      reinterpret_cast<NewReader>(ReaderModuleSymbol(path, "tetmesherNewSurfaceReader"));
    auto reader = vtk::TakeSmartPointer(newReader(ext.c_str()));
    reader->SetFileName(path.c_str());
    RunReader(reader, path);
    surface = reader->GetOutput();
  }
  else if (ext == ".vtp" || ext == ".vtk" || ext == ".vtu")
  {
    vtkSmartPointer<vtkDataSet> data = ReadVolumeMesh(path);
    surface = vtkPolyData::SafeDownCast(data);
    if (!surface)
    {
      // e.g. a surface stored in a .vtu
      using SurfaceOf = vtkPolyData* (*)(vtkDataSet*);
      auto surfaceOf = reinterpret_cast<SurfaceOf>(ReaderModuleSymbol(path, "tetmesherSurfaceOf"));
      surface = vtk::TakeSmartPointer(surfaceOf(data));
    }
  }
  else
  {
    Fail(path,
      "unknown surface type '" + ext +
        "' (use .stl .obj .ply .vtp .vtk .off, TetGen .smesh .poly .face, Gmsh .msh or "
        "Medit .mesh)");
  }
  return surface;
}

namespace
{
// Point ids and the cells' offsets below 2^31.
bool CellIdsFitInt32(vtkUnstructuredGrid* mesh)
{
  constexpr vtkIdType kMax = std::numeric_limits<std::int32_t>::max();
  return mesh->GetCells() && mesh->GetNumberOfPoints() <= kMax &&
    mesh->GetCells()->GetNumberOfConnectivityIds() <= kMax;
}
} // namespace

namespace
{
// The grid's tets, RegionId and InputFaceIds as WriteExportMesh takes them (the output of
// vtkTetMesher: every cell a VTK_TETRA).
void WriteExportFromGrid(vtkUnstructuredGrid* mesh, const std::string& path)
{
  const vtkIdType pointCount = mesh->GetNumberOfPoints();
  std::vector<double> points(3 * static_cast<std::size_t>(pointCount));
  for (vtkIdType p = 0; p < pointCount; ++p)
    mesh->GetPoint(p, &points[3 * static_cast<std::size_t>(p)]);
  const vtkIdType tetCount = mesh->GetNumberOfCells();
  std::vector<std::int64_t> cells;
  cells.reserve(4 * static_cast<std::size_t>(tetCount));
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < tetCount; ++c)
  {
    mesh->GetCellPoints(c, ids);
    if (mesh->GetCellType(c) != VTK_TETRA || ids->GetNumberOfIds() != 4)
      Fail(path, "cell " + std::to_string(c) + " is not a tetrahedron");
    for (vtkIdType i = 0; i < 4; ++i)
      cells.push_back(ids->GetId(i));
  }
  std::vector<std::int32_t> regions;
  std::vector<std::int64_t> faces;
  std::vector<double> attributes;
  vtkDataArray* regionArray = mesh->GetCellData()->GetArray("RegionId");
  vtkDataArray* attributeArray = mesh->GetCellData()->GetArray("RegionAttribute");
  for (vtkIdType c = 0; attributeArray && c < tetCount; ++c)
    attributes.push_back(attributeArray->GetComponent(c, 0));
  vtkDataArray* faceArray = mesh->GetCellData()->GetArray("InputFaceIds");
  for (vtkIdType c = 0; regionArray && c < tetCount; ++c)
    regions.push_back(static_cast<std::int32_t>(regionArray->GetComponent(c, 0)));
  if (faceArray && faceArray->GetNumberOfComponents() == 4)
    for (vtkIdType c = 0; c < tetCount; ++c)
      for (int i = 0; i < 4; ++i)
        faces.push_back(static_cast<std::int64_t>(faceArray->GetComponent(c, i)));
  ExportMesh out;
  out.points = points.data();
  out.pointCount = pointCount;
  out.cells = cells.data();
  out.tetCount = tetCount;
  out.regionIds = regions.empty() ? nullptr : regions.data();
  out.regionAttribute = attributes.empty() ? nullptr : attributes.data();
  out.inputFaceIds = faces.empty() ? nullptr : faces.data();
  WriteExportMesh(out, path);
}
} // namespace

void WriteVolumeMesh(vtkUnstructuredGrid* mesh, const std::string& path, bool compress)
{
  const std::string ext = LowerExtension(path);
  int ok = 0;
  if (ext == ".vtu")
  {
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    writer->SetFileName(path.c_str());
    writer->SetInputData(mesh);
    // Raw appended binary: zlib took 10% of a 160k-tet run's CPU time and base64 adds a third
    // to the size and its encoding time.
    writer->SetDataModeToAppended();
    writer->SetEncodeAppendedData(false);
    // The cells' ids as Int32 where they fit, as the lean writer (WriteVtu) stores them.
    if (CellIdsFitInt32(mesh))
      mesh->GetCells()->ConvertTo32BitStorage();
    if (compress)
      writer->SetCompressorTypeToZLib();
    else
      writer->SetCompressorTypeToNone();
    ok = Write(writer);
  }
  else if (ext == ".vtk")
  {
    vtkNew<vtkUnstructuredGridWriter> writer;
    writer->SetFileName(path.c_str());
    writer->SetInputData(mesh);
    writer->SetFileTypeToBinary();
    ok = Write(writer);
  }
  else if (IsExportExtension(ext))
  {
    WriteExportFromGrid(mesh, path);
    return;
  }
  else
  {
    Fail(path, "unknown output type '" + ext + "' (use .vtu, .vtk, .msh, .mesh, .node or .ele)");
  }
  if (!ok)
  {
    Fail(path, "could not be written");
  }
}

} // namespace cli
} // namespace tetmesher
