// CallVtkModule for the static executable. Linked statically, `tetmesher` starts ~0.7 ms
// sooner than with the shared C library (the loader, its relocations and three libraries'
// mappings: 2.3 against 2.9 ms for a one-tet mesh), but it cannot load VTK's shared
// libraries. What needs them (other formats, --background, --with-vtk, `quality`) is decided
// before any meshing or output, so the same command line is handed over whole to the dynamic
// twin, libexec/tetmesher-vtk, which loads them as the dynamic build does.
#include "CommandLine.h"
#include "InstallLayout.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <unistd.h>

namespace tetmesher
{
namespace cli
{
namespace
{
char** commandLine = nullptr;
} // namespace

void KeepCommandLine(int, char* argv[])
{
  commandLine = argv;
}

int CallVtkModule(const char*, const std::function<int(void*)>&)
{
  const std::string twin = PathBesideExecutable(TETMESHER_TWIN_DIR, "tetmesher-vtk");
  std::fflush(stdout);
  std::fflush(stderr);
  if (!twin.empty() && commandLine)
    execv(twin.c_str(), commandLine);
  if (twin.empty())
    std::fprintf(stderr, "tetmesher: cannot run its VTK part (its own path is unreadable)\n");
  else
    std::fprintf(
      stderr, "tetmesher: cannot run its VTK part (%s: %s)\n", twin.c_str(), std::strerror(errno));
  return 1;
}

} // namespace cli
} // namespace tetmesher
