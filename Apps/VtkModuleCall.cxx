// CallVtkModule for the dynamic executable: libtetmesherVtk.so loaded in the process.
#include "CommandLine.h"
#include "ModuleLoading.h"

#include <cstdio>
#include <dlfcn.h>

namespace tetmesher
{
namespace cli
{

void KeepCommandLine(int, char*[]) {}

int CallVtkModule(const char* symbol, const std::function<int(void*)>& call)
{
  static void* module = LoadModule("libtetmesherVtk.so");
  void* function = module ? dlsym(module, symbol) : nullptr;
  if (!function)
  {
    const char* why = dlerror();
    std::fprintf(stderr,
      "tetmesher: cannot load its VTK part (libtetmesherVtk.so: %s)\n",
      why ? why : "missing symbol");
    return 1;
  }
  return call(function);
}

} // namespace cli
} // namespace tetmesher
