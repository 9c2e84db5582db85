#include "Report.h"
#include "MeshReport.h"

#include "vtkAlgorithm.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkTable.h"

#include <cstdint>
#include <vector>

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

double FieldValue(vtkDataSet* mesh, const char* name)
{
  vtkDataArray* array = mesh->GetFieldData()->GetArray(name);
  return array ? array->GetComponent(0, 0) : 0.0;
}

void PrintQualityReport(std::FILE* out, const std::string& name, vtkDataSet* mesh)
{
  PrintQualityReport(
    out,
    name,
    static_cast<long long>(mesh->GetNumberOfPoints()),
    [mesh](const char* field) { return FieldValue(mesh, field); },
    mesh->GetFieldData()->GetArray("SurfaceQualityBound") != nullptr);
}

std::vector<std::int64_t> HistogramCounts(vtkTable* histogram)
{
  std::vector<std::int64_t> counts;
  vtkDataArray* count = vtkDataArray::SafeDownCast(histogram->GetColumnByName("Count"));
  for (vtkIdType i = 0; count && i < count->GetNumberOfTuples(); ++i)
    counts.push_back(static_cast<std::int64_t>(count->GetComponent(i, 0)));
  return counts;
}
} // namespace cli
} // namespace tetmesher
