// In a file of its own, so that the static executable, which never loads a module (it hands
// such work to its dynamic twin, VtkTwinCall.cxx), does not link it.
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
