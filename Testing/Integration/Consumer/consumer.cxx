// Quality of one right-corner tetrahedron through the installed TetMesher.
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkTetQuality.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <iostream>

int main()
{
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  points->InsertNextPoint(0, 1, 0);
  points->InsertNextPoint(0, 0, 1);
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  vtkIdType tet[4] = { 0, 1, 2, 3 };
  grid->InsertNextCell(VTK_TETRA, 4, tet);

  vtkNew<vtkTetQuality> quality;
  quality->SetInputData(grid);
  quality->Update();
  double q = quality->GetOutput()->GetCellData()->GetArray("Quality")->GetComponent(0, 0);
  std::cout << "Q = " << q << "\n"; // sqrt(3) - 1 = 0.732051
  return std::abs(q - (std::sqrt(3.0) - 1.0)) < 1e-12 ? 0 : 1;
}
