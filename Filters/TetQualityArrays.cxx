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

#include <cstdint>
#include <vector>

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
  std::vector<double> points(static_cast<std::size_t>(3 * pointCount));
  std::vector<double> sizes(size ? static_cast<std::size_t>(pointCount) : 0);
  for (vtkIdType p = 0; p < pointCount; ++p)
  {
    input->GetPoint(p, &points[static_cast<std::size_t>(3 * p)]);
    if (size)
      sizes[static_cast<std::size_t>(p)] = size->GetComponent(p, 0);
  }
  const vtkIdType cellCount = input->GetNumberOfCells();
  std::vector<std::int64_t> cells(static_cast<std::size_t>(4 * cellCount), -1);
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < cellCount; ++c)
  {
    if (input->GetCellType(c) != VTK_TETRA)
      continue;
    input->GetCellPoints(c, ids);
    for (int i = 0; i < 4; ++i)
      cells[static_cast<std::size_t>(4 * c + i)] = ids->GetId(i);
  }
  TetMeshView view;
  view.points = points.data();
  view.pointCount = pointCount;
  view.cells = cells.data();
  view.cellCount = cellCount;
  view.sizes = size ? sizes.data() : nullptr;
  view.sizeName = size && size->GetName() ? size->GetName() : "";
  return measureMesh(view, binCount, result, error);
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
  AddCellArray("Quality", result.quality, cellData);
  AddCellArray("MinDihedralAngle", result.minDihedral, cellData);
  AddCellArray("MaxDihedralAngle", result.maxDihedral, cellData);
  cellData->SetActiveScalars("Quality");
}

void AttachQualitySummary(const QualitySummary& summary, vtkFieldData* fieldData)
{
  for (const auto& [name, value] : qualitySummaryFields(summary))
    AddFieldScalar(fieldData, name, value);
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
