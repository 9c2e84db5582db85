// libtetmesherVtk.so: the commands that need VTK, loaded by tetmesher with dlopen only when
// a run needs them (its libraries' loading and static initialisers cost ~50 ms per run).
#include "CommandLine.h"
#include "MeshOptions.h"

#include "vtkSMPTools.h"

#include <cstdlib>

namespace
{
void UseSequentialBackend()
{
  // The mesher is sequential; VTK's threads (TBB) only parallelise array scans of the writer
  // and cost their start-up (~6 ms). VTK_SMP_BACKEND_IN_USE still chooses.
  if (!std::getenv("VTK_SMP_BACKEND_IN_USE"))
    vtkSMPTools::SetBackend("Sequential");
}
} // namespace

extern "C"
{
  __attribute__((visibility("default"))) int tetmesherMeshWithVtk(
    const tetmesher::cli::MeshOptions* options)
  {
    UseSequentialBackend();
    return tetmesher::cli::RunMeshWithVtk(*options);
  }

  __attribute__((visibility("default"))) int tetmesherQuality(int argc, char* argv[])
  {
    UseSequentialBackend();
    return tetmesher::cli::RunQuality(argc, argv);
  }
}
