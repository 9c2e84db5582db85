// VTK glue shared by vtkTetQuality and vtkTetMesher: measure every tet of a dataset with the
// core's measureMesh and turn the results into VTK arrays, field data and a histogram table.
#pragma once

#include "TetQuality.h"

#include <string>
#include <vector>

class vtkCellData;
class vtkDataArray;
class vtkDataSet;
class vtkFieldData;
class vtkTable;

namespace tetmesher
{
namespace vtkglue
{

using TetQualityResult = MeshQuality;

// Measures every VTK_TETRA cell of `input` (measureMesh of the core). `size` (optional) is a
// point array of h > 0. Returns false with `error` naming the defect (no tetrahedra, a
// non-finite coordinate, a bad size value) and where it is.
bool ComputeTetQuality(vtkDataSet* input,
  vtkDataArray* size,
  int binCount,
  TetQualityResult& result,
  std::string& error);

void AttachQualityArrays(const TetQualityResult& result, vtkCellData* cellData);
// Adds a one-value double array `name` to field data (the summary numbers).
void AddFieldScalar(vtkFieldData* fieldData, const char* name, double value);

void AttachQualitySummary(const QualitySummary& summary, vtkFieldData* fieldData);
void FillHistogramTable(const std::vector<std::int64_t>& bins, vtkTable* table);

} // namespace vtkglue
} // namespace tetmesher
