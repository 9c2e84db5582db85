// The subcommands of `tetmesher`. Each returns the process exit status (0 ok, 1 bad input or
// failure, 2 wrong usage).
#pragma once

#include <functional>

namespace tetmesher
{
namespace cli
{
struct MeshOptions;

// In the executable: `mesh` on the lean path, or through the VTK module when it must.
int RunMesh(int argc, char* argv[]);
// Loads libtetmesherVtk.so and calls `call` with its function `symbol`; on failure prints
// why and returns 1 (VtkModuleCall.cxx). In the static executable, which cannot load it, runs
// the same command line in its dynamic twin instead and does not return on success
// (VtkTwinCall.cxx).
int CallVtkModule(const char* symbol, const std::function<int(void*)>& call);
// The executable's command line, for the twin (main keeps it before any command runs).
void KeepCommandLine(int argc, char* argv[]);
// In the VTK module (libtetmesherVtk.so).
int RunMeshWithVtk(const MeshOptions& options);
int RunQuality(int argc, char* argv[]);
} // namespace cli
} // namespace tetmesher
