// On its own: the static executable must not link dlopen (it
// cannot load modules that need the shared C library; VtkTwinCall.cxx runs its twin instead).
#include "ModuleLoading.h"
#include "InstallLayout.h"

#include <dlfcn.h>

namespace tetmesher
{
namespace cli
{

void* LoadModule(const char* fileName)
{
  const std::string path = PathBesideExecutable(TETMESHER_MODULE_DIR, fileName);
  if (!path.empty())
    if (void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL))
      return module;
  return dlopen(fileName, RTLD_NOW | RTLD_LOCAL);
}

} // namespace cli
} // namespace tetmesher
