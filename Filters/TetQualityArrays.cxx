#include "TetQualityArrays.h"

#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkTable.h"

#include <cmath>
#include <limits>
#include <sstream>

namespace tetmesher
{
namespace vtkglue
{

bool ComputeTetQuality(vtkDataSet* input,
  vtkDataArray* size,
  int binCount,
  TetQualityResult& result,
  std::string& error)
{
  const vtkIdType pointCount = input->GetNumberOfPoints();
  for (vtkIdType p = 0; p < pointCount; ++p)
  {
    double x[3];
    input->GetPoint(p, x);
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
    {
      std::ostringstream message;
      message << "point " << p << " has a non-finite coordinate (" << x[0] << ", " << x[1] << ", "
              << x[2] << ")";
      error = message.str();
      return false;
    }
    if (size)
    {
      double h = size->GetComponent(p, 0);
      if (!(h > 0) || !std::isfinite(h))
      {
        std::ostringstream message;
        message << "size array '" << (size->GetName() ? size->GetName() : "")
                << "' has the invalid value " << h << " at point " << p
                << " (sizes must be finite and > 0)";
        error = message.str();
        return false;
      }
    }
  }

  const vtkIdType cellCount = input->GetNumberOfCells();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  result.Quality.assign(static_cast<std::size_t>(cellCount), nan);
  result.MinDihedral.assign(static_cast<std::size_t>(cellCount), nan);
  result.MaxDihedral.assign(static_cast<std::size_t>(cellCount), nan);
  std::vector<TetShape> shapes;
  shapes.reserve(static_cast<std::size_t>(cellCount));
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < cellCount; ++c)
  {
    if (input->GetCellType(c) != VTK_TETRA)
    {
      continue;
    }
    input->GetCellPoints(c, ids);
    double x[4][3];
    double h[4] = { 1, 1, 1, 1 };
    for (int i = 0; i < 4; ++i)
    {
      input->GetPoint(ids->GetId(i), x[i]);
      if (size)
      {
        h[i] = size->GetComponent(ids->GetId(i), 0);
      }
    }
    TetShape shape =
      size ? measureTetScaled(x[0], x[1], x[2], x[3], h) : measureTet(x[0], x[1], x[2], x[3]);
    result.Quality[static_cast<std::size_t>(c)] = shape.quality;
    result.MinDihedral[static_cast<std::size_t>(c)] = shape.minDihedral;
    result.MaxDihedral[static_cast<std::size_t>(c)] = shape.maxDihedral;
    shapes.push_back(shape);
  }
  if (shapes.empty())
  {
    std::ostringstream message;
    message << "the input has no tetrahedra (" << cellCount << " cells, none of type VTK_TETRA)";
    error = message.str();
    return false;
  }
  result.Summary = summarizeQuality(shapes);
  result.Histogram = qualityHistogram(shapes, binCount);
  return true;
}

namespace
{
void AddCellArray(const char* name, const std::vector<double>& values, vtkCellData* cellData)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    array->SetValue(static_cast<vtkIdType>(i), values[i]);
  }
  cellData->AddArray(array);
}

} // namespace

void AddFieldScalar(vtkFieldData* fieldData, const char* name, double value)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfTuples(1);
  array->SetValue(0, value);
  fieldData->AddArray(array);
}

void AttachQualityArrays(const TetQualityResult& result, vtkCellData* cellData)
{
  AddCellArray("Quality", result.Quality, cellData);
  AddCellArray("MinDihedralAngle", result.MinDihedral, cellData);
  AddCellArray("MaxDihedralAngle", result.MaxDihedral, cellData);
  cellData->SetActiveScalars("Quality");
}

void AttachQualitySummary(const QualitySummary& summary, vtkFieldData* fieldData)
{
  AddFieldScalar(fieldData, "TetrahedronCount", static_cast<double>(summary.count));
  AddFieldScalar(fieldData, "QualityMinimum", summary.minimum);
  AddFieldScalar(fieldData, "QualityMean", summary.mean);
  AddFieldScalar(fieldData, "QualityPercentile1", summary.percentile1);
  AddFieldScalar(fieldData, "QualityShareBelow0.1", summary.shareBelow01);
  AddFieldScalar(fieldData, "QualityShareBelow0.3", summary.shareBelow03);
  AddFieldScalar(fieldData, "MinDihedralAngle", summary.minDihedral);
  AddFieldScalar(fieldData, "MaxDihedralAngle", summary.maxDihedral);
}

void FillHistogramTable(const std::vector<std::int64_t>& bins, vtkTable* table)
{
  table->Initialize();
  vtkNew<vtkDoubleArray> start, end, center;
  vtkNew<vtkIdTypeArray> count;
  start->SetName("BinStart");
  end->SetName("BinEnd");
  center->SetName("BinCenter");
  count->SetName("Count");
  const double width = 1.0 / static_cast<double>(bins.size());
  for (std::size_t i = 0; i < bins.size(); ++i)
  {
    start->InsertNextValue(width * static_cast<double>(i));
    end->InsertNextValue(width * static_cast<double>(i + 1));
    center->InsertNextValue(width * (static_cast<double>(i) + 0.5));
    count->InsertNextValue(static_cast<vtkIdType>(bins[i]));
  }
  table->AddColumn(center);
  table->AddColumn(count);
  table->AddColumn(start);
  table->AddColumn(end);
}

} // namespace vtkglue
} // namespace tetmesher
