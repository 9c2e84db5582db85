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
// why and returns 1.
int CallVtkModule(const char* symbol, const std::function<int(void*)>& call);
// In the VTK module (libtetmesherVtk.so).
int RunMeshWithVtk(const MeshOptions& options);
int RunQuality(int argc, char* argv[]);
} // namespace cli
} // namespace tetmesher
