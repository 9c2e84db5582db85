#include "vtkTetQuality.h"

#include "TetQualityArrays.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkTable.h"

vtkStandardNewMacro(vtkTetQuality);

vtkTetQuality::vtkTetQuality()
{
  this->SetNumberOfOutputPorts(2);
}

vtkTetQuality::~vtkTetQuality()
{
  this->SetSizeArrayName(nullptr);
}

void vtkTetQuality::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SizeArrayName: " << (this->SizeArrayName ? this->SizeArrayName : "(none)")
     << "\n";
  os << indent << "NumberOfBins: " << this->NumberOfBins << "\n";
}

vtkTable* vtkTetQuality::GetHistogramOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

int vtkTetQuality::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTable");
    return 1;
  }
  return this->Superclass::FillOutputPortInformation(port, info);
}

int vtkTetQuality::RequestDataObject(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  if (!input)
  {
    return 0;
  }
  vtkInformation* info0 = outputVector->GetInformationObject(0);
  vtkDataSet* output = vtkDataSet::SafeDownCast(info0->Get(vtkDataObject::DATA_OBJECT()));
  if (!output || !output->IsA(input->GetClassName()))
  {
    vtkDataSet* fresh = input->NewInstance();
    info0->Set(vtkDataObject::DATA_OBJECT(), fresh);
    fresh->Delete();
  }
  vtkInformation* info1 = outputVector->GetInformationObject(1);
  if (!vtkTable::SafeDownCast(info1->Get(vtkDataObject::DATA_OBJECT())))
  {
    auto table = vtkSmartPointer<vtkTable>::New();
    info1->Set(vtkDataObject::DATA_OBJECT(), table);
  }
  return 1;
}

int vtkTetQuality::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkDataSet* output = vtkDataSet::GetData(outputVector, 0);
  vtkTable* histogram = vtkTable::GetData(outputVector, 1);
  output->ShallowCopy(input);

  vtkDataArray* size = nullptr;
  if (this->SizeArrayName && *this->SizeArrayName)
  {
    size = input->GetPointData()->GetArray(this->SizeArrayName);
    if (!size)
    {
      vtkErrorMacro(<< "SizeArrayName names point array '" << this->SizeArrayName
                    << "', which the input does not have.");
      return 0;
    }
  }

  tetmesher::vtkglue::TetQualityResult result;
  std::string error;
  if (!tetmesher::vtkglue::ComputeTetQuality(input, size, this->NumberOfBins, result, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  tetmesher::vtkglue::AttachQualityArrays(result, output->GetCellData());
  tetmesher::vtkglue::AttachQualitySummary(result.summary, output->GetFieldData());
  tetmesher::vtkglue::FillHistogramTable(result.histogram, histogram);
  tetmesher::vtkglue::AttachQualitySummary(result.summary, histogram->GetFieldData());
  return 1;
}
