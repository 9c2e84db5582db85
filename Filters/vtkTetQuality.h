/**
 * @class   vtkTetQuality
 * @brief   Shape quality of tetrahedra: Q = 2*sqrt(6)*r_in/l_max and dihedral angles.
 *
 * For any dataset of tetrahedra, adds cell arrays `Quality` (1 for the regular tet, 0 for a
 * flat or inverted one), `MinDihedralAngle` and `MaxDihedralAngle` (degrees). When
 * SizeArrayName names a point array h (> 0), lengths are measured in units of h, as in
 * George-Hecht-Saltel 1990 section 4.2 (the size-scaled Q).
 *
 * Output port 1 is a vtkTable histogram of Q (columns `BinStart`, `BinEnd`, `BinCenter`,
 * `Count`), the paper's figure 6, plottable in ParaView's bar chart. Summary statistics
 * (`QualityMinimum`, `QualityMean`, `QualityPercentile1`, `QualityShareBelow0.1`,
 * `QualityShareBelow0.3`, `MinDihedralAngle`, `MaxDihedralAngle`, `TetrahedronCount`)
 * are stored in the field data of both outputs. Cells that are not tetrahedra get NaN and
 * are left out of the statistics. The filter fails with an error naming the defect when the
 * input has no tetrahedra, a non-finite coordinate, or an invalid size value.
 */
#ifndef vtkTetQuality_h
#define vtkTetQuality_h

#include "vtkDataSetAlgorithm.h"
#include "vtkFiltersTetMesherModule.h" // for export macro

class vtkTable;

class VTKFILTERSTETMESHER_EXPORT vtkTetQuality : public vtkDataSetAlgorithm
{
public:
  static vtkTetQuality* New();
  vtkTypeMacro(vtkTetQuality, vtkDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Name of a point array holding the wanted edge length h at each point. Empty (the
   * default): plain lengths.
   */
  vtkSetStringMacro(SizeArrayName);
  vtkGetStringMacro(SizeArrayName);
  ///@}

  ///@{
  /**
   * Number of equal bins of the Q histogram over [0, 1]. Default 20.
   */
  vtkSetClampMacro(NumberOfBins, int, 1, 10000);
  vtkGetMacro(NumberOfBins, int);
  ///@}

  /**
   * The histogram table (output port 1).
   */
  vtkTable* GetHistogramOutput();

protected:
  vtkTetQuality();
  ~vtkTetQuality() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* SizeArrayName = nullptr;
  int NumberOfBins = 20;

private:
  vtkTetQuality(const vtkTetQuality&) = delete;
  void operator=(const vtkTetQuality&) = delete;
};

#endif
