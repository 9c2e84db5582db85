#include "vtkTetMesher.h"

#include "MemoryBudget.h"
#include "MeshAssembly.h"
#include "SurfaceDiagnosis.h"
#include "TetQualityArrays.h"
#include "VolumeMesher.h"

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
#include "vtkPolygon.h"
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
// The core orients tets with Shewchuk's orient3d > 0; VTK_TETRA wants the opposite (the
// right-hand normal of points 0,1,2 towards point 3). Swapping points 0 and 1 converts, and
// swaps the faces opposite them.
constexpr int kVtkFromCore[4] = { 1, 0, 2, 3 };

// The input cells and points named by the diagnosis, for users to see them (ParaView: colour
// output 2 by DefectKind). Triangles become polygons, lone points vertices; cell data
// DefectKind (the SurfaceDefect value), DefectRecord (which record), InputCellId; field data
// DefectSummary (the text of the error).
void FillDefects(const tetmesher::SurfaceDiagnosis& diagnosis,
  vtkPolyData* input,
  const std::vector<vtkIdType>& cellOfTriangle,
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
        input->GetCellPoints(cell, ids);
        polys->InsertNextCell(ids);
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

} // namespace

vtkTetMesher::vtkTetMesher()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(3);
  this->SetControllingSpaceArrayName("h");
}

vtkTetMesher::~vtkTetMesher()
{
  this->SetSizeArrayName(nullptr);
  this->SetControllingSpaceArrayName(nullptr);
}

void vtkTetMesher::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EnclosedShellsAreHoles: " << this->EnclosedShellsAreHoles << "\n";
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
  if (input->GetNumberOfStrips() > 0)
  {
    return fail("the input has triangle strips: convert them to triangles first "
                "(vtkTriangleFilter)");
  }
  // Input cell ids of polygons come after the vertices and lines of a vtkPolyData.
  const vtkIdType firstPolyId = input->GetNumberOfVerts() + input->GetNumberOfLines();
  std::vector<std::int32_t> triangles;
  std::vector<vtkIdType> cellOfTriangle; // the input cell each triangle comes from
  triangles.reserve(static_cast<std::size_t>(3 * input->GetNumberOfPolys()));
  vtkIdType triangulatedPolygons = 0;
  {
    vtkNew<vtkPolygon> polygon;
    vtkNew<vtkIdList> fan;
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
        triangles.insert(triangles.end(),
          { static_cast<std::int32_t>(ids[0]),
            static_cast<std::int32_t>(ids[1]),
            static_cast<std::int32_t>(ids[2]) });
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
      // Split it into triangles of its own points (the surface keeps its points).
      polygon->Initialize(static_cast<int>(size), ids, input->GetPoints());
      if (!polygon->Triangulate(fan) || fan->GetNumberOfIds() != 3 * (size - 2))
      {
        // Ear cutting needs a planar polygon. Otherwise fan from its first point; should
        // the fan fold over, the input check reports the resulting intersections.
        fan->Reset();
        for (vtkIdType k = 1; k + 1 < size; ++k)
        {
          fan->InsertNextId(0);
          fan->InsertNextId(k);
          fan->InsertNextId(k + 1);
        }
      }
      for (vtkIdType k = 0; k < fan->GetNumberOfIds(); k += 3)
      {
        for (int c = 0; c < 3; ++c)
        {
          triangles.push_back(static_cast<std::int32_t>(ids[fan->GetId(k + c)]));
        }
        cellOfTriangle.push_back(cellId);
      }
      ++triangulatedPolygons;
    }
  }
  std::vector<double> coords(static_cast<std::size_t>(3 * pointCount));
  for (vtkIdType p = 0; p < pointCount; ++p)
  {
    input->GetPoint(p, &coords[static_cast<std::size_t>(3 * p)]);
  }
  const auto triangleCount = static_cast<std::int32_t>(triangles.size() / 3);
  lap("input conversion");

  defects->Initialize();
  if (this->CheckInput)
  {
    tetmesher::DiagnosisOptions diagnosisOptions;
    diagnosisOptions.maxRecordsPerKind = 1000;
    tetmesher::SurfaceDiagnosis diagnosis = tetmesher::diagnoseSurface(coords.data(),
      static_cast<std::int32_t>(pointCount),
      triangles.data(),
      triangleCount,
      diagnosisOptions);
    FillDefects(diagnosis, input, cellOfTriangle, defects);
    if (!diagnosis.ok())
    {
      std::string summary = diagnosis.summary(10);
      if (firstPolyId > 0 || triangulatedPolygons > 0)
      {
        summary += "\n(triangle ids count the triangles of the input's polygons in order; "
                   "input cell ids differ when the input has vertices, lines or polygons)";
      }
      return fail("the input surface cannot be meshed:\n" + summary);
    }
    lap("input diagnosis");
  }
  this->UpdateProgress(0.05);

  // --- Size field sources ---------------------------------------------------------------
  tetmesher::VolumeMeshOptions options;
  if (this->SizeArrayName && *this->SizeArrayName && this->Refine)
  {
    vtkDataArray* sizes = input->GetPointData()->GetArray(this->SizeArrayName);
    if (!sizes)
    {
      return fail(std::string("SizeArrayName names point array '") + this->SizeArrayName +
        "', which the input surface does not have");
    }
    options.inputSizes.resize(static_cast<std::size_t>(pointCount));
    for (vtkIdType p = 0; p < pointCount; ++p)
    {
      const double h = sizes->GetComponent(p, 0);
      if (!(h > 0) || !std::isfinite(h))
      {
        std::ostringstream message;
        message << "size array '" << this->SizeArrayName << "' has the invalid value " << h
                << " at point " << p << " (sizes must be finite and > 0)";
        return fail(message.str());
      }
      options.inputSizes[static_cast<std::size_t>(p)] = h;
    }
  }
  ControllingSpace space;
  if (this->Refine && this->GetNumberOfInputConnections(1) > 0)
  {
    std::string error = space.Initialize(vtkDataSet::GetData(inputVector[1]),
      this->ControllingSpaceArrayName ? this->ControllingSpaceArrayName : "");
    if (!error.empty())
    {
      return fail("controlling space: " + error);
    }
    if (options.inputSizes.empty())
    {
      options.background = [&space](const double* x) { return space.SizeAt(x); };
    }
  }

  // --- Mesh ------------------------------------------------------------------------------
  // The surface was checked above (or the user chose not to): not twice.
  options.boundary.validateInput = false;
  options.boundary.enclosedShellsAreHoles = this->EnclosedShellsAreHoles;
  options.boundary.maxSteinerPoints = this->MaximumSteinerPoints;
  options.boundary.removeSteinerPoints = this->RemoveSteinerPoints;
  options.refine = this->Refine;
  options.refinement.size.scale = this->SizeScale;
  options.refinement.size.minSize = this->MinSize;
  options.refinement.size.maxSize = this->MaxSize;
  options.refinement.size.gradation = this->Gradation;
  options.refinement.size.interpolationPower = this->InterpolationPower;
  options.optimize = this->Optimize && this->OptimizationPasses > 0;
  options.optimization.passes = this->OptimizationPasses;
  options.optimization.qualityTarget = this->QualityTarget;
  options.optimization.dihedralTarget = this->DihedralTarget;
  options.optimization.measure = this->QualityMeasure == MIN_DIHEDRAL
    ? tetmesher::QualityMeasure::MinDihedral
    : tetmesher::QualityMeasure::PaperQ;
  options.boundary.maxSeconds = this->TimeLimit;
  // MemoryLimit in MB; 0: what the machine has available now; < 0: no check.
  options.refinement.memoryLimitBytes = this->MemoryLimit > 0 ? this->MemoryLimit * 1e6
    : this->MemoryLimit == 0                                  ? tetmesher::availableMemoryBytes()
                                                              : 0.0;
  options.boundary.memoryLimitBytes = options.refinement.memoryLimitBytes;
  lap("size sources");
  const auto start = std::chrono::steady_clock::now();
  bool outOfTime = false;
  tetmesher::VolumeMeshResult result = tetmesher::meshVolume(coords.data(),
    static_cast<std::int32_t>(pointCount),
    triangles.data(),
    triangleCount,
    options,
    [this, start, &outOfTime](double progress)
    {
      this->UpdateProgress(0.05 + 0.85 * progress);
      if (this->TimeLimit > 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
          this->TimeLimit)
      {
        outOfTime = true;
        return false;
      }
      return !this->GetAbortExecute();
    });
  if (this->GetAbortExecute())
  {
    return fail("meshing was aborted");
  }
  if (outOfTime && !result.ok)
  {
    std::ostringstream message;
    message << "meshing exceeded the time limit of " << this->TimeLimit << " s (" << result.error
            << ")";
    return fail(message.str());
  }
  if (!result.ok)
  {
    return fail(result.error);
  }

  for (const auto& [stage, seconds] : result.stageSeconds)
  {
    char text[32];
    std::snprintf(text, sizeof text, "%.4f\t", seconds);
    this->StageTimings += text + stage + "\n";
  }
  lapStart = std::chrono::steady_clock::now();

  // --- Convert back ------------------------------------------------------------------------
  const vtkIdType outPointCount = static_cast<vtkIdType>(result.points.size() / 3);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(outPointCount);
  for (vtkIdType p = 0; p < outPointCount; ++p)
  {
    points->SetPoint(p, &result.points[static_cast<std::size_t>(3 * p)]);
  }
  output->SetPoints(points);

  const vtkIdType tetCount = static_cast<vtkIdType>(result.tets.size() / 4);
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfTuples(tetCount + 1);
  connectivity->SetNumberOfTuples(4 * tetCount);
  for (vtkIdType t = 0; t < tetCount; ++t)
  {
    offsets->SetValue(t, 4 * t);
    for (int i = 0; i < 4; ++i)
    {
      connectivity->SetValue(
        4 * t + i, result.tets[static_cast<std::size_t>(4 * t + kVtkFromCore[i])]);
    }
  }
  offsets->SetValue(tetCount, 4 * tetCount);
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  output->SetCells(VTK_TETRA, cells);

  vtkNew<vtkIntArray> regionIds;
  regionIds->SetName("RegionId");
  regionIds->SetNumberOfTuples(tetCount);
  for (vtkIdType t = 0; t < tetCount; ++t)
  {
    regionIds->SetValue(t, result.regionIds[static_cast<std::size_t>(t)]);
  }
  output->GetCellData()->AddArray(regionIds);

  vtkNew<vtkIdTypeArray> inputFaces;
  inputFaces->SetName("InputFaceIds");
  inputFaces->SetNumberOfComponents(4);
  inputFaces->SetNumberOfTuples(tetCount);
  inputFaces->Fill(-1);
  // Every tet face lying on an input triangle (both sides of an interface triangle).
  const std::vector<std::int32_t> faceTriangle =
    tetmesher::tetFaceTriangles(result.tets, triangles.data(), triangleCount);
  for (vtkIdType t = 0; t < tetCount; ++t)
  {
    for (int f = 0; f < 4; ++f)
    {
      const std::int32_t tri = faceTriangle[static_cast<std::size_t>(4 * t + f)];
      if (tri >= 0)
        inputFaces->SetTypedComponent(
          t, kVtkFromCore[f], cellOfTriangle[static_cast<std::size_t>(tri)]);
    }
  }
  output->GetCellData()->AddArray(inputFaces);
  lap("output conversion");

  // Quality with the same code as vtkTetQuality.
  tetmesher::vtkglue::TetQualityResult quality;
  std::string qualityError;
  if (!tetmesher::vtkglue::ComputeTetQuality(
        output, nullptr, this->NumberOfBins, quality, qualityError))
  {
    return fail("quality of the result: " + qualityError);
  }
  tetmesher::vtkglue::AttachQualityArrays(quality, output->GetCellData());
  vtkFieldData* fieldData = output->GetFieldData();
  tetmesher::vtkglue::AttachQualitySummary(quality.Summary, fieldData);
  tetmesher::vtkglue::AddFieldScalar(fieldData, "SteinerPointCount", result.steinerPoints);
  tetmesher::vtkglue::AddFieldScalar(fieldData, "InteriorPointCount", result.interiorPoints);
  tetmesher::vtkglue::AddFieldScalar(fieldData, "RegionCount", result.regionCount);
  tetmesher::vtkglue::AddFieldScalar(
    fieldData, "TriangulatedPolygonCount", static_cast<double>(triangulatedPolygons));
  tetmesher::vtkglue::AddFieldScalar(fieldData, "MeshingSeconds", result.seconds);
  if (!result.vertexSize.empty())
  {
    vtkNew<vtkDoubleArray> h;
    h->SetName("h");
    h->SetNumberOfTuples(outPointCount);
    for (vtkIdType p = 0; p < outPointCount; ++p)
    {
      h->SetValue(p, result.vertexSize[static_cast<std::size_t>(p)]);
    }
    output->GetPointData()->AddArray(h);
  }
  lap("quality arrays");
  tetmesher::vtkglue::FillHistogramTable(quality.Histogram, histogram);
  // The paper's figure 6 shows the histogram before and after optimisation. Only Q is used:
  // measureTetForOptimization gives it bit for bit with one arc cosine fewer per tet.
  {
    std::vector<tetmesher::TetShape> before;
    before.reserve(result.tetsBeforeOptimization.size() / 4);
    for (std::size_t t = 0; t + 3 < result.tetsBeforeOptimization.size(); t += 4)
    {
      const double* p[4];
      for (int i = 0; i < 4; ++i)
      {
        p[i] = &result.points[3 *
          static_cast<std::size_t>(
            result.tetsBeforeOptimization[t + static_cast<std::size_t>(kVtkFromCore[i])])];
      }
      before.push_back(tetmesher::measureTetForOptimization(p[0], p[1], p[2], p[3], nullptr));
    }
    if (!before.empty())
    {
      std::vector<std::int64_t> bins = tetmesher::qualityHistogram(before, this->NumberOfBins);
      vtkNew<vtkIdTypeArray> counts;
      counts->SetName("CountBeforeOptimization");
      for (std::int64_t n : bins)
      {
        counts->InsertNextValue(static_cast<vtkIdType>(n));
      }
      histogram->AddColumn(counts);
      tetmesher::vtkglue::AddFieldScalar(
        fieldData, "QualityMinimumBeforeOptimization", tetmesher::summarizeQuality(before).minimum);
    }
  }
  tetmesher::vtkglue::AttachQualitySummary(quality.Summary, histogram->GetFieldData());
  lap("histograms");
  this->UpdateProgress(1.0);
  return 1;
}
