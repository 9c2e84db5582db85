#include "vtkTetMesher.h"

#include "PolygonTriangulation.h"
#include "SurfaceDiagnosis.h"
#include "SurfaceMeshing.h"
#include "TetQualityArrays.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkGenericCell.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <sstream>
#include <unordered_map>
#include <vector>

vtkStandardNewMacro(vtkTetMesher);

namespace
{
// The input cells and points named by the diagnosis, for users to see them (ParaView: colour
// output 2 by DefectKind). Triangles become their input polygons (a triangle of a strip
// itself: its cell is the whole strip), lone points vertices; cell data DefectKind (the
// SurfaceDefect value), DefectRecord (which record), InputCellId; field data DefectSummary
// (the text of the error).
void FillDefects(const tetmesher::SurfaceDiagnosis& diagnosis,
  vtkPolyData* input,
  const std::vector<std::int32_t>& triangles,
  const std::vector<std::int64_t>& cellOfTriangle,
  vtkPolyData* defects)
{
  defects->Initialize();
  if (diagnosis.defects.empty())
  {
    return;
  }
  defects->SetPoints(input->GetPoints());
  vtkNew<vtkCellArray> polys, verts;
  vtkNew<vtkIntArray> polyKind, vertKind, polyRecord, vertRecord;
  vtkNew<vtkIdTypeArray> polyCell, vertCell;
  vtkNew<vtkIdList> ids;
  for (std::size_t r = 0; r < diagnosis.defects.size(); ++r)
  {
    const tetmesher::DefectRecord& record = diagnosis.defects[r];
    const int kind = static_cast<int>(record.kind);
    if (!record.triangleIds.empty())
    {
      for (std::int32_t tri : record.triangleIds)
      {
        if (tri < 0 || static_cast<std::size_t>(tri) >= cellOfTriangle.size())
        {
          continue;
        }
        const vtkIdType cell = cellOfTriangle[static_cast<std::size_t>(tri)];
        if (input->GetCellType(cell) == VTK_TRIANGLE_STRIP)
        {
          const vtkIdType corners[3] = { triangles[3 * static_cast<std::size_t>(tri)],
            triangles[3 * static_cast<std::size_t>(tri) + 1],
            triangles[3 * static_cast<std::size_t>(tri) + 2] };
          polys->InsertNextCell(3, corners);
        }
        else
        {
          input->GetCellPoints(cell, ids);
          polys->InsertNextCell(ids);
        }
        polyKind->InsertNextValue(kind);
        polyRecord->InsertNextValue(static_cast<int>(r));
        polyCell->InsertNextValue(cell);
      }
    }
    else
    {
      for (std::int32_t point : record.pointIds)
      {
        if (point < 0 || point >= input->GetNumberOfPoints())
        {
          continue;
        }
        const vtkIdType id = point;
        verts->InsertNextCell(1, &id);
        vertKind->InsertNextValue(kind);
        vertRecord->InsertNextValue(static_cast<int>(r));
        vertCell->InsertNextValue(-1);
      }
    }
  }
  defects->SetVerts(verts);
  defects->SetPolys(polys);
  // vtkPolyData orders cells verts first, then polys: so must the cell arrays.
  vtkNew<vtkIntArray> kinds, records;
  vtkNew<vtkIdTypeArray> cells;
  kinds->SetName("DefectKind");
  records->SetName("DefectRecord");
  cells->SetName("InputCellId");
  for (vtkIntArray* part : { vertKind.Get(), polyKind.Get() })
    for (vtkIdType i = 0; i < part->GetNumberOfTuples(); ++i)
      kinds->InsertNextValue(part->GetValue(i));
  for (vtkIntArray* part : { vertRecord.Get(), polyRecord.Get() })
    for (vtkIdType i = 0; i < part->GetNumberOfTuples(); ++i)
      records->InsertNextValue(part->GetValue(i));
  for (vtkIdTypeArray* part : { vertCell.Get(), polyCell.Get() })
    for (vtkIdType i = 0; i < part->GetNumberOfTuples(); ++i)
      cells->InsertNextValue(part->GetValue(i));
  vtkNew<vtkStringArray> labels; // readable and categorical in ParaView's colour map
  labels->SetName("Defect");
  for (vtkIdType i = 0; i < kinds->GetNumberOfTuples(); ++i)
    labels->InsertNextValue(
      tetmesher::defectLabel(static_cast<tetmesher::SurfaceDefect>(kinds->GetValue(i)), false));
  defects->GetCellData()->AddArray(labels);
  defects->GetCellData()->AddArray(kinds);
  defects->GetCellData()->AddArray(records);
  defects->GetCellData()->AddArray(cells);
  defects->GetCellData()->SetActiveScalars("DefectKind");
  vtkNew<vtkStringArray> summary;
  summary->SetName("DefectSummary");
  summary->InsertNextValue(diagnosis.summary(10));
  defects->GetFieldData()->AddArray(summary);
}

// A controlling space: h anywhere from a dataset's point array, interpolated in its cells;
// outside them, the value at the nearest point.
class ControllingSpace
{
public:
  std::string Initialize(vtkDataSet* data, const std::string& arrayName)
  {
    if (!data || data->GetNumberOfPoints() == 0)
      return "the dataset on input port 1 is empty";
    this->Sizes = data->GetPointData()->GetArray(arrayName.c_str());
    if (!this->Sizes)
      return "it has no point array '" + arrayName + "' (set ControllingSpaceArrayName)";
    for (vtkIdType p = 0; p < data->GetNumberOfPoints(); ++p)
    {
      const double h = this->Sizes->GetComponent(p, 0);
      if (!(h > 0) || !std::isfinite(h))
      {
        std::ostringstream message;
        message << "array '" << arrayName << "' has the invalid size " << h << " at point " << p;
        return message.str();
      }
    }
    this->Data = data;
    // FindCell's tolerance is a squared distance: relative to the dataset's size, so that a
    // controlling space at 1e-12 or 1e12 behaves as one at unit scale.
    const double length = data->GetLength();
    this->Tolerance2 = length > 0 ? 1e-18 * length * length : 0.0;
    this->Weights.resize(static_cast<std::size_t>(std::max(data->GetMaxCellSize(), 1)));
    return "";
  }

  double SizeAt(const double* x)
  {
    double point[3] = { x[0], x[1], x[2] };
    double pcoords[3];
    int subId = 0;
    const vtkIdType cell = this->Data->FindCell(
      point, nullptr, this->Cell, -1, this->Tolerance2, subId, pcoords, this->Weights.data());
    if (cell >= 0)
    {
      this->Data->GetCellPoints(cell, this->Ids);
      double h = 0;
      for (vtkIdType i = 0; i < this->Ids->GetNumberOfIds(); ++i)
        h += this->Weights[static_cast<std::size_t>(i)] *
          this->Sizes->GetComponent(this->Ids->GetId(i), 0);
      if (h > 0)
        return h;
    }
    return this->Sizes->GetComponent(this->Data->FindPoint(point), 0);
  }

private:
  vtkDataSet* Data = nullptr;
  vtkDataArray* Sizes = nullptr;
  double Tolerance2 = 0;
  vtkNew<vtkGenericCell> Cell;
  vtkNew<vtkIdList> Ids;
  std::vector<double> Weights;
};

// One property and its field of the core's settings, copied one way or the other.
template<typename Get, typename Set, typename T>
void Exchange(vtkTetMesher* filter,
  tetmesher::SurfaceMeshSettings& settings,
  bool toFilter,
  Get get,
  Set set,
  T tetmesher::SurfaceMeshSettings::*field)
{
  if (toFilter)
    (filter->*set)(settings.*field);
  else
    settings.*field = (filter->*get)();
}

// The filter's properties that are the core job's settings, in one list for both directions:
// the constructor takes the core's defaults, RequestData hands the properties to the core.
void ExchangeSettings(vtkTetMesher* f, tetmesher::SurfaceMeshSettings& s, bool toFilter)
{
  using M = vtkTetMesher;
  using S = tetmesher::SurfaceMeshSettings;
  Exchange(f, s, toFilter, &M::GetCheckInput, &M::SetCheckInput, &S::checkInput);
  Exchange(f,
    s,
    toFilter,
    &M::GetEnclosedShellsAreHoles,
    &M::SetEnclosedShellsAreHoles,
    &S::enclosedShellsAreHoles);
  Exchange(f, s, toFilter, &M::GetInnerFacets, &M::SetInnerFacets, &S::innerFacets);
  Exchange(f,
    s,
    toFilter,
    &M::GetMaximumSteinerPoints,
    &M::SetMaximumSteinerPoints,
    &S::maximumSteinerPoints);
  Exchange(f,
    s,
    toFilter,
    &M::GetRemoveSteinerPoints,
    &M::SetRemoveSteinerPoints,
    &S::removeSteinerPoints);
  Exchange(f, s, toFilter, &M::GetRefine, &M::SetRefine, &S::refine);
  Exchange(f, s, toFilter, &M::GetSizeScale, &M::SetSizeScale, &S::sizeScale);
  Exchange(f, s, toFilter, &M::GetMinSize, &M::SetMinSize, &S::minSize);
  Exchange(f, s, toFilter, &M::GetMaxSize, &M::SetMaxSize, &S::maxSize);
  Exchange(f, s, toFilter, &M::GetGradation, &M::SetGradation, &S::gradation);
  Exchange(
    f, s, toFilter, &M::GetInterpolationPower, &M::SetInterpolationPower, &S::interpolationPower);
  Exchange(f, s, toFilter, &M::GetOptimize, &M::SetOptimize, &S::optimize);
  Exchange(
    f, s, toFilter, &M::GetOptimizationPasses, &M::SetOptimizationPasses, &S::optimizationPasses);
  Exchange(f, s, toFilter, &M::GetQualityTarget, &M::SetQualityTarget, &S::qualityTarget);
  Exchange(f, s, toFilter, &M::GetDihedralTarget, &M::SetDihedralTarget, &S::dihedralTarget);
  Exchange(f, s, toFilter, &M::GetTimeLimit, &M::SetTimeLimit, &S::timeLimit);
  Exchange(f, s, toFilter, &M::GetMemoryLimit, &M::SetMemoryLimit, &S::memoryLimit);
  Exchange(f, s, toFilter, &M::GetNumberOfBins, &M::SetNumberOfBins, &S::numberOfBins);
  if (toFilter)
    f->SetQualityMeasure(
      s.measure == tetmesher::QualityMeasure::MinDihedral ? M::MIN_DIHEDRAL : M::PAPER_Q);
  else
    s.measure = f->GetQualityMeasure() == M::MIN_DIHEDRAL ? tetmesher::QualityMeasure::MinDihedral
                                                          : tetmesher::QualityMeasure::PaperQ;
}
} // namespace

vtkTetMesher::vtkTetMesher()
{
  tetmesher::SurfaceMeshSettings defaults;
  ExchangeSettings(this, defaults, true);
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(3);
  this->SetControllingSpaceArrayName("h");
}

vtkTetMesher::~vtkTetMesher()
{
  this->SetSizeArrayName(nullptr);
  this->SetControllingSpaceArrayName(nullptr);
  this->SetHolePoints(nullptr);
}

vtkCxxSetObjectMacro(vtkTetMesher, HolePoints, vtkPoints);

void vtkTetMesher::AddHolePoint(double x, double y, double z)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble(); // the CLI's doubles: the same regions on both paths
  if (this->HolePoints)
    for (vtkIdType i = 0; i < this->HolePoints->GetNumberOfPoints(); ++i)
      points->InsertNextPoint(this->HolePoints->GetPoint(i));
  points->InsertNextPoint(x, y, z);
  this->SetHolePoints(points);
}

void vtkTetMesher::AddRegionPoint(double x, double y, double z, double attribute)
{
  this->AddRegionPoint(x, y, z, attribute, 0.0);
}

void vtkTetMesher::AddRegionPoint(double x, double y, double z, double attribute, double maxSize)
{
  this->RegionPoints.insert(this->RegionPoints.end(), { x, y, z, attribute });
  this->RegionMaxSizes.push_back(maxSize);
  this->Modified();
}

void vtkTetMesher::RemoveAllRegionPoints()
{
  if (!this->RegionPoints.empty())
  {
    this->RegionPoints.clear();
    this->RegionMaxSizes.clear();
    this->Modified();
  }
}

int vtkTetMesher::GetNumberOfRegionPoints()
{
  return static_cast<int>(this->RegionPoints.size() / 4);
}

void vtkTetMesher::AddInteriorPoint(double x, double y, double z)
{
  this->InteriorPoints.insert(this->InteriorPoints.end(), { x, y, z });
  this->Modified();
}

void vtkTetMesher::RemoveAllInteriorPoints()
{
  if (!this->InteriorPoints.empty())
  {
    this->InteriorPoints.clear();
    this->Modified();
  }
}

int vtkTetMesher::GetNumberOfInteriorPoints()
{
  return static_cast<int>(this->InteriorPoints.size() / 3);
}

void vtkTetMesher::RemoveAllHolePoints()
{
  if (this->HolePoints && this->HolePoints->GetNumberOfPoints() > 0)
    this->SetHolePoints(nullptr);
}

vtkMTimeType vtkTetMesher::GetMTime()
{
  const vtkMTimeType own = this->Superclass::GetMTime();
  return this->HolePoints ? std::max(own, this->HolePoints->GetMTime()) : own;
}

void vtkTetMesher::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EnclosedShellsAreHoles: " << this->EnclosedShellsAreHoles << "\n";
  os << indent << "InnerFacets: " << this->InnerFacets << "\n";
  os << indent
     << "HolePoints: " << (this->HolePoints ? this->HolePoints->GetNumberOfPoints() : vtkIdType(0))
     << "\n";
  os << indent << "RegionPoints: " << this->RegionPoints.size() / 4 << "\n";
  os << indent << "InteriorPoints: " << this->InteriorPoints.size() / 3 << "\n";
  os << indent << "MaximumSteinerPoints: " << this->MaximumSteinerPoints << "\n";
  os << indent << "RemoveSteinerPoints: " << this->RemoveSteinerPoints << "\n";
  os << indent << "CheckInput: " << this->CheckInput << "\n";
  os << indent << "TriangulatePolygons: " << this->TriangulatePolygons << "\n";
  os << indent << "NumberOfBins: " << this->NumberOfBins << "\n";
  os << indent << "Refine: " << this->Refine << "\n";
  os << indent << "SizeArrayName: " << (this->SizeArrayName ? this->SizeArrayName : "(none)")
     << "\n";
  os << indent << "ControllingSpaceArrayName: "
     << (this->ControllingSpaceArrayName ? this->ControllingSpaceArrayName : "(none)") << "\n";
  os << indent << "SizeScale: " << this->SizeScale << "\n";
  os << indent << "MinSize: " << this->MinSize << "\n";
  os << indent << "MaxSize: " << this->MaxSize << "\n";
  os << indent << "Gradation: " << this->Gradation << "\n";
  os << indent << "InterpolationPower: " << this->InterpolationPower << "\n";
  os << indent << "Optimize: " << this->Optimize << "\n";
  os << indent << "OptimizationPasses: " << this->OptimizationPasses << "\n";
  os << indent << "QualityTarget: " << this->QualityTarget << "\n";
  os << indent << "QualityMeasure: " << this->QualityMeasure << "\n";
  os << indent << "DihedralTarget: " << this->DihedralTarget << "\n";
  os << indent << "TimeLimit: " << this->TimeLimit << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << "\n";
}

vtkTable* vtkTetMesher::GetHistogramOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

vtkPolyData* vtkTetMesher::GetDefectsOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(2));
}

int vtkTetMesher::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkTetMesher::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTable");
    return 1;
  }
  if (port == 2)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkPolyData");
    return 1;
  }
  return this->Superclass::FillOutputPortInformation(port, info);
}

int vtkTetMesher::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector, 0);
  vtkTable* histogram = vtkTable::GetData(outputVector, 1);
  vtkPolyData* defects = vtkPolyData::GetData(outputVector, 2);
  this->LastError.clear();
  this->LastWarnings.clear();
  this->StageTimings.clear();
  auto lapStart = std::chrono::steady_clock::now();
  auto lap = [this, &lapStart](const std::string& stage)
  {
    const auto now = std::chrono::steady_clock::now();
    char seconds[32];
    std::snprintf(
      seconds, sizeof seconds, "%.4f\t", std::chrono::duration<double>(now - lapStart).count());
    this->StageTimings += seconds + stage + "\n";
    lapStart = now;
  };
  auto fail = [this](const std::string& message)
  {
    this->LastError = message;
    vtkErrorMacro(<< message);
    return 0;
  };

  // --- Validate and convert the input -------------------------------------------------
  const vtkIdType pointCount = input->GetNumberOfPoints();
  if (pointCount > std::numeric_limits<std::int32_t>::max() / 2)
  {
    return fail("the input has too many points for 32-bit ids");
  }
  // Input cell ids of polygons come after the vertices and lines of a vtkPolyData.
  const vtkIdType firstPolyId = input->GetNumberOfVerts() + input->GetNumberOfLines();
  std::vector<double> coords(static_cast<std::size_t>(3 * pointCount));
  for (vtkIdType p = 0; p < pointCount; ++p)
  {
    input->GetPoint(p, &coords[static_cast<std::size_t>(3 * p)]);
  }
  std::vector<std::int32_t> triangles;
  std::vector<std::int64_t> cellOfTriangle; // the input cell each triangle comes from
  triangles.reserve(static_cast<std::size_t>(3 * input->GetNumberOfPolys()));
  vtkIdType triangulatedPolygons = 0;
  // An id beyond 32 bits becomes -1, which the input check names as out of range (a cast would
  // wrap it to a valid id).
  auto pointId = [](vtkIdType id)
  {
    return id < std::numeric_limits<std::int32_t>::min() ||
        id > std::numeric_limits<std::int32_t>::max()
      ? std::int32_t(-1)
      : static_cast<std::int32_t>(id);
  };
  {
    std::vector<std::int64_t> corners;
    std::vector<std::int32_t> local;
    auto iter = vtk::TakeSmartPointer(input->GetPolys()->NewIterator());
    vtkIdType polyIndex = 0;
    for (iter->GoToFirstCell(); !iter->IsDoneWithTraversal(); iter->GoToNextCell(), ++polyIndex)
    {
      vtkIdType size;
      const vtkIdType* ids;
      iter->GetCurrentCell(size, ids);
      const vtkIdType cellId = firstPolyId + polyIndex;
      if (size == 3)
      {
        triangles.insert(triangles.end(), { pointId(ids[0]), pointId(ids[1]), pointId(ids[2]) });
        cellOfTriangle.push_back(cellId);
        continue;
      }
      std::ostringstream message;
      message << "input cell " << cellId << " is a polygon with " << size << " points";
      if (size < 3 || !this->TriangulatePolygons)
      {
        return fail(message.str() +
          (size < 3 ? ""
                    : ": only triangles are meshed (turn "
                      "TriangulatePolygons on, or use vtkTriangleFilter)"));
      }
      // Split it into triangles of its own points (the surface keeps its points), as the
      // command line's lean path does.
      corners.assign(ids, ids + size);
      local.clear();
      tetmesher::triangulatePolygon(coords.data(), pointCount, corners.data(), size, local);
      for (std::size_t k = 0; k < local.size(); k += 3)
      {
        for (int c = 0; c < 3; ++c)
        {
          triangles.push_back(pointId(corners[static_cast<std::size_t>(local[k + c])]));
        }
        cellOfTriangle.push_back(cellId);
      }
      ++triangulatedPolygons;
    }
  }
  // Triangle strips (after the polygons in cell id order), as vtkTriangleStrip decomposes
  // them: every other triangle turned so that all keep the strip's orientation. Triangles with
  // a repeated point id are the joints that stitch strips together, not surface: left out.
  const vtkIdType stripCount = input->GetNumberOfStrips();
  if (stripCount > 0)
  {
    auto iter = vtk::TakeSmartPointer(input->GetStrips()->NewIterator());
    vtkIdType stripIndex = 0;
    for (iter->GoToFirstCell(); !iter->IsDoneWithTraversal(); iter->GoToNextCell(), ++stripIndex)
    {
      vtkIdType size;
      const vtkIdType* ids;
      iter->GetCurrentCell(size, ids);
      const vtkIdType cellId = firstPolyId + input->GetNumberOfPolys() + stripIndex;
      if (size < 3)
      {
        std::ostringstream message;
        message << "input cell " << cellId << " is a triangle strip with " << size << " points";
        return fail(message.str());
      }
      for (vtkIdType k = 0; k + 2 < size; ++k)
      {
        const vtkIdType a = ids[k], b = ids[k + 1], c = ids[k + 2];
        if (a == b || b == c || a == c)
          continue;
        if (k % 2 == 0)
          triangles.insert(triangles.end(), { pointId(a), pointId(b), pointId(c) });
        else
          triangles.insert(triangles.end(), { pointId(b), pointId(a), pointId(c) });
        cellOfTriangle.push_back(cellId);
      }
    }
  }
  const auto triangleCount = static_cast<std::int32_t>(triangles.size() / 3);
  lap("input conversion");

  // --- Mesh and the output's arrays (the core's job, shared with the command line) --------
  tetmesher::SurfaceMeshInput job;
  job.points = coords.data();
  job.pointCount = static_cast<std::int32_t>(pointCount);
  job.triangles = triangles.data();
  job.triangleCount = triangleCount;
  job.cellOfTriangle = cellOfTriangle.data();
  job.triangleIdsAreNotCellIds = firstPolyId > 0 || triangulatedPolygons > 0 || stripCount > 0;
  job.triangulatedPolygons = static_cast<double>(triangulatedPolygons);
  job.regionPoints = this->RegionPoints;
  job.regionMaxSizes = this->RegionMaxSizes;
  job.interiorPoints = this->InteriorPoints;
  if (this->HolePoints)
    for (vtkIdType i = 0; i < this->HolePoints->GetNumberOfPoints(); ++i)
    {
      double x[3];
      this->HolePoints->GetPoint(i, x);
      job.holePoints.insert(job.holePoints.end(), x, x + 3);
    }
  if (this->SizeArrayName && *this->SizeArrayName)
  {
    job.sizeArrayName = this->SizeArrayName;
    job.readSizeArray = [this, input, pointCount](std::vector<double>& sizes)
    {
      vtkDataArray* array = input->GetPointData()->GetArray(this->SizeArrayName);
      if (!array)
        return false;
      sizes.resize(static_cast<std::size_t>(pointCount));
      for (vtkIdType p = 0; p < pointCount; ++p)
        sizes[static_cast<std::size_t>(p)] = array->GetComponent(p, 0);
      return true;
    };
  }
  ControllingSpace space;
  if (this->GetNumberOfInputConnections(1) > 0)
  {
    job.prepareBackground = [&](std::function<double(const double*)>& sizeAt)
    {
      std::string error = space.Initialize(vtkDataSet::GetData(inputVector[1]),
        this->ControllingSpaceArrayName ? this->ControllingSpaceArrayName : "");
      sizeAt = [&space](const double* x) { return space.SizeAt(x); };
      return error;
    };
  }
  job.progress = [this](double progress)
  {
    this->UpdateProgress(progress);
    return !this->GetAbortExecute();
  };
  tetmesher::SurfaceMeshSettings settings;
  ExchangeSettings(this, settings, false);
  defects->Initialize();
  const tetmesher::SurfaceMeshOutput result = tetmesher::meshSurface(job, settings);
  this->StageTimings += result.stageTimings;
  this->LastWarnings = result.warnings;
  if (this->CheckInput)
  {
    FillDefects(result.diagnosis, input, triangles, cellOfTriangle, defects);
  }
  if (!result.ok)
  {
    return fail(result.error);
  }
  lapStart = std::chrono::steady_clock::now();

  // --- Convert to VTK ----------------------------------------------------------------------
  const vtkIdType outPointCount = static_cast<vtkIdType>(result.mesh.points.size() / 3);
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(outPointCount);
  std::copy(result.mesh.points.begin(), result.mesh.points.end(), coordinates->GetPointer(0));
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  output->SetPoints(points);

  const vtkIdType tetCount = static_cast<vtkIdType>(result.cells.size() / 4);
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfTuples(tetCount + 1);
  for (vtkIdType t = 0; t <= tetCount; ++t)
  {
    offsets->SetValue(t, 4 * t);
  }
  connectivity->SetNumberOfTuples(4 * tetCount);
  std::copy(result.cells.begin(), result.cells.end(), connectivity->GetPointer(0));
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  output->SetCells(VTK_TETRA, cells);

  vtkNew<vtkIntArray> regionIds;
  regionIds->SetName("RegionId");
  regionIds->SetNumberOfTuples(tetCount);
  std::copy(result.mesh.regionIds.begin(), result.mesh.regionIds.end(), regionIds->GetPointer(0));
  output->GetCellData()->AddArray(regionIds);
  if (!result.regionAttribute.empty())
  {
    vtkNew<vtkDoubleArray> attributes;
    attributes->SetName("RegionAttribute");
    attributes->SetNumberOfTuples(tetCount);
    std::copy(
      result.regionAttribute.begin(), result.regionAttribute.end(), attributes->GetPointer(0));
    output->GetCellData()->AddArray(attributes);
  }

  vtkNew<vtkIdTypeArray> inputFaces;
  inputFaces->SetName("InputFaceIds");
  inputFaces->SetNumberOfComponents(4);
  inputFaces->SetNumberOfTuples(tetCount);
  std::copy(result.inputFaceIds.begin(), result.inputFaceIds.end(), inputFaces->GetPointer(0));
  output->GetCellData()->AddArray(inputFaces);

  tetmesher::vtkglue::AttachQualityArrays(result.quality, output->GetCellData());
  vtkFieldData* fieldData = output->GetFieldData();
  for (const auto& [name, value] : result.fieldData)
  {
    tetmesher::vtkglue::AddFieldScalar(fieldData, name.c_str(), value);
  }
  if (!result.mesh.vertexSize.empty())
  {
    vtkNew<vtkDoubleArray> h;
    h->SetName("h");
    h->SetNumberOfTuples(outPointCount);
    std::copy(result.mesh.vertexSize.begin(), result.mesh.vertexSize.end(), h->GetPointer(0));
    output->GetPointData()->AddArray(h);
  }
  tetmesher::vtkglue::FillHistogramTable(result.quality.histogram, histogram);
  if (!result.histogramBefore.empty())
  {
    vtkNew<vtkIdTypeArray> counts;
    counts->SetName("CountBeforeOptimization");
    for (std::int64_t n : result.histogramBefore)
    {
      counts->InsertNextValue(static_cast<vtkIdType>(n));
    }
    histogram->AddColumn(counts);
  }
  tetmesher::vtkglue::AttachQualitySummary(result.quality.summary, histogram->GetFieldData());
  lap("VTK output");
  this->UpdateProgress(1.0);
  return 1;
}
