// The command line's reports of VTK objects (printed by MeshReport.h), and running a VTK
// filter with its errors caught.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkDataSet;
class vtkTable;

namespace tetmesher
{
namespace cli
{
// Updates the filter; returns its error messages (empty on success) instead of letting VTK
// print them with source locations.
std::string RunFilter(vtkAlgorithm* filter);

// "NAME: N tetrahedra, M points" and the quality summary from the field data.
void PrintQualityReport(std::FILE* out, const std::string& name, vtkDataSet* mesh);

// The Count column of a histogram table (vtkTetQuality's, vtkTetMesher's).
std::vector<std::int64_t> HistogramCounts(vtkTable* histogram);

// A value of the field data (0 when missing).
double FieldValue(vtkDataSet* mesh, const char* name);
} // namespace cli
} // namespace tetmesher
