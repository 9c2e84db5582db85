// libtetmesherVtk.so: the commands that need VTK, loaded by tetmesher with dlopen only when
// a run needs them (its libraries' loading and static initialisers cost ~50 ms per run).
#include "CommandLine.h"
#include "MeshOptions.h"

#include "vtkSMPTools.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>

namespace
{
void UseSequentialBackend()
{
  // The mesher is sequential; VTK's threads (TBB) only parallelise array scans of the writer
  // and cost their start-up (~6 ms). VTK_SMP_BACKEND_IN_USE still chooses.
  if (!std::getenv("VTK_SMP_BACKEND_IN_USE"))
    vtkSMPTools::SetBackend("Sequential");
}
// No exception leaves the module: these are C functions, and tetmesher has its own copy of
// the C++ runtime (linked statically), whose handlers would not match this one's types.
template<typename Command>
int Guarded(Command&& command)
{
  try
  {
    return command();
  }
  catch (const std::bad_alloc&)
  {
    std::fputs("tetmesher: out of memory\n", stderr);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "tetmesher: %s\n", e.what());
  }
  return 1;
}
} // namespace

extern "C"
{
  __attribute__((visibility("default"))) int tetmesherMeshWithVtk(
    const tetmesher::cli::MeshOptions* options)
  {
    UseSequentialBackend();
    return Guarded([options] { return tetmesher::cli::RunMeshWithVtk(*options); });
  }

  __attribute__((visibility("default"))) int tetmesherQuality(int argc, char* argv[])
  {
    UseSequentialBackend();
    return Guarded([argc, argv] { return tetmesher::cli::RunQuality(argc, argv); });
  }
}
