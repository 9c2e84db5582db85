// Image regression: a tet mesh coloured by Quality, compared with the baseline
// Testing/Data/Baseline/TestTetQualityRender.png.
#include "vtkTetQuality.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataSetMapper.h"
#include "vtkNew.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkXMLUnstructuredGridReader.h"

int TestTetQualityRender(int argc, char* argv[])
{
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(TETMESHER_TEST_DATA_DIR "/jittered-cube.vtu");

  vtkNew<vtkTetQuality> quality;
  quality->SetInputConnection(reader->GetOutputPort());

  vtkNew<vtkDataSetMapper> mapper;
  mapper->SetInputConnection(quality->GetOutputPort(0));
  mapper->SetScalarModeToUseCellFieldData();
  mapper->SelectColorArray("Quality");
  mapper->SetScalarRange(0.0, 1.0);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->EdgeVisibilityOn();

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(1, 1, 1);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(300, 300);
  window->AddRenderer(renderer);
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);

  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(2.6, -1.8, 2.2);
  camera->SetFocalPoint(0.5, 0.5, 0.5);
  camera->SetViewUp(0, 0, 1);
  renderer->ResetCameraClippingRange();
  window->Render();

  int result = vtkRegressionTestImage(window);
  if (result == vtkRegressionTester::DO_INTERACTOR)
  {
    interactor->Start();
  }
  return result == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}
