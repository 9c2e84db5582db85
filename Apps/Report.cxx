#include "Report.h"

#include "vtkAlgorithm.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkTable.h"

#include <algorithm>

namespace tetmesher
{
namespace cli
{
namespace
{
class ErrorText : public vtkCommand
{
public:
  static ErrorText* New() { return new ErrorText; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    std::string message = data ? static_cast<const char*>(data) : "";
    // Drop VTK's "ERROR: In file, line N\nvtkClass (0x..): " prefix: keep the last line.
    while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
      message.pop_back();
    auto colon = message.rfind("): ");
    if (colon != std::string::npos)
      message = message.substr(colon + 3);
    if (!Text.empty())
      Text += "; ";
    Text += message;
  }
  std::string Text;
};

double Field(vtkDataSet* mesh, const char* name)
{
  vtkDataArray* array = mesh->GetFieldData()->GetArray(name);
  return array ? array->GetComponent(0, 0) : 0.0;
}
} // namespace

std::string RunFilter(vtkAlgorithm* filter)
{
  // The executive repeats every failure as its own error: observe it too, and keep ours.
  vtkNew<ErrorText> errors, pipelineErrors;
  filter->AddObserver(vtkCommand::ErrorEvent, errors);
  filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, pipelineErrors);
  filter->Update();
  filter->RemoveObserver(errors);
  filter->GetExecutive()->RemoveObserver(pipelineErrors);
  if (errors->Text.empty() && !pipelineErrors->Text.empty())
    return "the pipeline failed";
  return errors->Text;
}

void PrintQualityReport(std::FILE* out, const std::string& name, vtkDataSet* mesh)
{
  std::fprintf(out,
    "%s: %lld tetrahedra, %lld points\n",
    name.c_str(),
    static_cast<long long>(Field(mesh, "TetrahedronCount")),
    static_cast<long long>(mesh->GetNumberOfPoints()));
  std::fprintf(out,
    "  quality Q   min %.4f  mean %.4f  1st percentile %.4f\n",
    Field(mesh, "QualityMinimum"),
    Field(mesh, "QualityMean"),
    Field(mesh, "QualityPercentile1"));
  std::fprintf(out,
    "  share       Q < 0.1: %.3f%%  Q < 0.3: %.3f%%\n",
    100.0 * Field(mesh, "QualityShareBelow0.1"),
    100.0 * Field(mesh, "QualityShareBelow0.3"));
  std::fprintf(out,
    "  dihedral    min %.2f deg  max %.2f deg\n",
    Field(mesh, "MinDihedralAngle"),
    Field(mesh, "MaxDihedralAngle"));
}

void PrintHistogram(std::FILE* out, vtkTable* histogram)
{
  vtkDataArray* start = vtkDataArray::SafeDownCast(histogram->GetColumnByName("BinStart"));
  vtkDataArray* end = vtkDataArray::SafeDownCast(histogram->GetColumnByName("BinEnd"));
  vtkDataArray* count = vtkDataArray::SafeDownCast(histogram->GetColumnByName("Count"));
  if (!start || !end || !count)
    return;
  double largest = 1;
  for (vtkIdType i = 0; i < count->GetNumberOfTuples(); ++i)
    largest = std::max(largest, count->GetComponent(i, 0));
  std::fprintf(out, "  histogram of Q\n");
  for (vtkIdType i = 0; i < count->GetNumberOfTuples(); ++i)
  {
    double n = count->GetComponent(i, 0);
    int bar = static_cast<int>(40.0 * n / largest + 0.5);
    std::fprintf(out,
      "  %.2f-%.2f %10lld %s\n",
      start->GetComponent(i, 0),
      end->GetComponent(i, 0),
      static_cast<long long>(n),
      std::string(static_cast<std::size_t>(bar), '#').c_str());
  }
}
} // namespace cli
} // namespace tetmesher
