// The command line's reports of VTK objects (printed by MeshReport.h), and running a VTK
// filter with its errors caught.
#pragma once

#include <cstdio>
#include <string>

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

void PrintHistogram(std::FILE* out, vtkTable* histogram);
} // namespace cli
} // namespace tetmesher
