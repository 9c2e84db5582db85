// vtkTetQuality on hand-computed tetrahedra: the formula, the size scaling, the summary,
// the histogram, and the errors on bad input.
#include "vtkTetQuality.h"

#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkTable.h"
#include "vtkUnstructuredGrid.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace
{
int failures = 0;

void Check(bool condition, const std::string& what)
{
  if (!condition)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++failures;
  }
}

void CheckNear(double value, double expected, double tolerance, const std::string& what)
{
  Check(std::abs(value - expected) <= tolerance,
    what + ": got " + std::to_string(value) + ", expected " + std::to_string(expected));
}

class ErrorCounter : public vtkCommand
{
public:
  static ErrorCounter* New() { return new ErrorCounter; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    ++Count;
    Last = data ? static_cast<const char*>(data) : "";
  }
  int Count = 0;
  std::string Last;
};

vtkSmartPointer<vtkUnstructuredGrid> MakeGrid(const std::vector<std::array<double, 3>>& points,
  const std::vector<std::array<vtkIdType, 4>>& tets)
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  for (const auto& p : points)
  {
    pts->InsertNextPoint(p.data());
  }
  grid->SetPoints(pts);
  for (const auto& t : tets)
  {
    grid->InsertNextCell(VTK_TETRA, 4, t.data());
  }
  return grid;
}

double CellValue(vtkTetQuality* filter, const char* name, vtkIdType cell)
{
  auto output = vtkDataSet::SafeDownCast(filter->GetOutputDataObject(0));
  return output->GetCellData()->GetArray(name)->GetComponent(cell, 0);
}

double FieldValue(vtkTetQuality* filter, const char* name)
{
  auto output = vtkDataSet::SafeDownCast(filter->GetOutputDataObject(0));
  vtkDataArray* array = output->GetFieldData()->GetArray(name);
  Check(array != nullptr, std::string("field data ") + name);
  return array ? array->GetComponent(0, 0) : std::numeric_limits<double>::quiet_NaN();
}

const double s3 = std::sqrt(3.0);
const double s6 = std::sqrt(6.0);

// Regular tet of edge 1 in VTK orientation, right-corner tet, a nearly flat tet, a flat one.
std::vector<std::array<double, 3>> kPoints = {
  { 0, 0, 0 },
  { 1, 0, 0 },
  { 0.5, s3 / 2, 0 },
  { 0.5, s3 / 6, std::sqrt(2.0 / 3.0) }, // 0-3
  { 0, 1, 0 },
  { 0, 0, 1 }, // 4-5
  { 0.5, 0.5, 1e-9 },
  { 0.5, 0.5, 0 } // 6-7
};
} // namespace

int TestTetQuality(int, char*[])
{
  auto grid = MakeGrid(kPoints, { { 0, 1, 2, 3 }, { 0, 1, 4, 5 }, { 0, 1, 4, 6 }, { 0, 1, 4, 7 } });
  vtkNew<vtkTetQuality> filter;
  filter->SetInputData(grid);
  filter->SetNumberOfBins(10);
  filter->Update();

  // Regular tet: Q = 1, all dihedral angles acos(1/3).
  const double regularAngle = std::acos(1.0 / 3.0) * 180.0 / M_PI;
  CheckNear(CellValue(filter, "Quality", 0), 1.0, 1e-12, "regular tet Q");
  CheckNear(CellValue(filter, "MinDihedralAngle", 0), regularAngle, 1e-9, "regular min angle");
  CheckNear(CellValue(filter, "MaxDihedralAngle", 0), regularAngle, 1e-9, "regular max angle");
  // Right-corner tet: r = 1/(3+sqrt3), lmax = sqrt2, so Q = 2 sqrt6 r / sqrt2 = sqrt3 - 1.
  CheckNear(CellValue(filter, "Quality", 1), s3 - 1.0, 1e-12, "corner tet Q");
  CheckNear(CellValue(filter, "MinDihedralAngle", 1),
    std::acos(1.0 / s3) * 180.0 / M_PI,
    1e-9,
    "corner tet min angle");
  CheckNear(CellValue(filter, "MaxDihedralAngle", 1), 90.0, 1e-9, "corner tet max angle");
  // Nearly flat: Q tends to 0 (here about 1e-9 scale); exactly flat: Q = 0.
  Check(CellValue(filter, "Quality", 2) < 1e-8, "nearly flat tet Q ~ 0");
  Check(CellValue(filter, "Quality", 2) > 0, "nearly flat tet Q > 0");
  CheckNear(CellValue(filter, "Quality", 3), 0.0, 0.0, "flat tet Q");
  CheckNear(CellValue(filter, "MaxDihedralAngle", 3), 180.0, 1e-9, "flat tet max angle");

  // Summary: 4 tets; Q = {1, sqrt3-1, ~0, 0}.
  CheckNear(FieldValue(filter, "TetrahedronCount"), 4, 0, "count");
  CheckNear(FieldValue(filter, "QualityMinimum"), 0.0, 0.0, "min");
  CheckNear(FieldValue(filter, "QualityMean"),
    (1.0 + s3 - 1.0 + CellValue(filter, "Quality", 2)) / 4,
    1e-12,
    "mean");
  CheckNear(FieldValue(filter, "QualityShareBelow0.1"), 0.5, 0, "share < 0.1");
  CheckNear(FieldValue(filter, "QualityShareBelow0.3"), 0.5, 0, "share < 0.3");
  CheckNear(FieldValue(filter, "QualityPercentile1"), 0.0, 0, "1st percentile");

  // Histogram: 10 bins over [0,1], counts sum to 4, Q=1 in the last bin, sqrt3-1 in bin 7.
  vtkTable* histogram = filter->GetHistogramOutput();
  Check(histogram->GetNumberOfRows() == 10, "10 histogram rows");
  auto count = vtkDataArray::SafeDownCast(histogram->GetColumnByName("Count"));
  Check(count != nullptr, "Count column");
  if (count)
  {
    CheckNear(count->GetComponent(0, 0), 2, 0, "bin 0");
    CheckNear(count->GetComponent(7, 0), 1, 0, "bin 7");
    CheckNear(count->GetComponent(9, 0), 1, 0, "bin 9");
  }

  // Size scaling. Constant h: unchanged. h = (1,1,1,2) on the regular tet: lmax_h = 1
  // (base edges), harmonic mean of h = 4/3.5, so Q_h = 1 / (4/3.5) = 0.875.
  for (double constant : { 1.0, 2.5 })
  {
    vtkNew<vtkDoubleArray> h;
    h->SetName("h");
    h->SetNumberOfTuples(grid->GetNumberOfPoints());
    h->Fill(constant);
    grid->GetPointData()->AddArray(h);
    filter->SetSizeArrayName("h");
    filter->Update();
    CheckNear(CellValue(filter, "Quality", 0), 1.0, 1e-12, "regular Q, constant h");
    CheckNear(CellValue(filter, "Quality", 1), s3 - 1.0, 1e-12, "corner Q, constant h");
  }
  grid->GetPointData()->GetArray("h")->Fill(1.0);
  grid->GetPointData()->GetArray("h")->SetComponent(3, 0, 2.0);
  grid->Modified();
  filter->Update();
  CheckNear(CellValue(filter, "Quality", 0), 0.875, 1e-12, "regular Q with h = (1,1,1,2)");
  (void)s6;

  // Bad input: each refused with an error naming the defect. The errors are expected: the
  // observers keep them off the output, where the test driver would count them as failures.
  auto expectError = [](vtkDataSet* input, const char* sizeName, const std::string& expected)
  {
    vtkNew<vtkTetQuality> bad;
    vtkNew<ErrorCounter> errors;
    vtkNew<ErrorCounter> pipelineErrors;
    bad->AddObserver(vtkCommand::ErrorEvent, errors);
    bad->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, pipelineErrors);
    bad->SetInputData(input);
    if (sizeName)
      bad->SetSizeArrayName(sizeName);
    bad->Update();
    Check(errors->Count > 0 && errors->Last.find(expected) != std::string::npos,
      "expected an error containing '" + expected + "', got '" + errors->Last + "'");
  };
  auto noTets = MakeGrid(kPoints, {});
  expectError(noTets, nullptr, "no tetrahedra");
  auto withNaN = MakeGrid(kPoints, { { 0, 1, 2, 3 } });
  withNaN->GetPoints()->SetPoint(2, 0.5, std::numeric_limits<double>::quiet_NaN(), 0);
  expectError(withNaN, nullptr, "point 2 has a non-finite coordinate");
  expectError(grid, "nosuch", "'nosuch'");
  grid->GetPointData()->GetArray("h")->SetComponent(5, 0, 0.0);
  grid->Modified();
  expectError(grid, "h", "invalid value 0 at point 5");

  std::cout << (failures ? "TestTetQuality: FAILED\n" : "TestTetQuality: all checks passed\n");
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
