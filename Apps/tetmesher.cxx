// tetmesher: the command-line front end.
//   tetmesher quality MESH [--size-array NAME] [--histogram]
//   tetmesher mesh SURFACE -o OUT.vtu [options]
// Exit status: 0 success, 1 bad input or failure (the message names file and defect),
// 2 wrong usage.
// The executable does not link VTK: `mesh` from .off/.vtp/.stl (and TetGen's and Gmsh's
// surface files) to .vtu runs the core
// directly (LeanMeshCommand.cxx); the rest is in libtetmesherVtk.so, loaded when needed.
#include "CommandLine.h"

#include <cstdio>
#include <string>

namespace
{
const char* const kUsage = R"(usage: tetmesher COMMAND [ARGS]

Boundary-conforming tetrahedral meshing for VTK.

commands:
  quality MESH   print the quality summary of a tetrahedral mesh
                 (.vtu .vtk, TetGen .node/.ele, Gmsh ASCII .msh)
  mesh SURFACE   tetrahedralize a closed triangulated surface
                 (.stl .obj .ply .vtp .vtk .off, TetGen .smesh .poly
                 .face, Gmsh .msh), boundary kept exactly;
                 writes .vtu .vtk, Gmsh .msh, TetGen .node/.ele/.face

Run 'tetmesher COMMAND --help' for the options of a command.
)";
}

int main(int argc, char* argv[])
{
  tetmesher::cli::KeepCommandLine(argc, argv);
  if (argc < 2)
  {
    std::fputs(kUsage, stderr);
    return 2;
  }
  const std::string command = argv[1];
  if (command == "--help" || command == "-h" || command == "help")
  {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (command == "mesh")
  {
    return tetmesher::cli::RunMesh(argc - 2, argv + 2);
  }
  if (command == "quality")
  {
    return tetmesher::cli::CallVtkModule("tetmesherQuality",
      [&](void* function)
      {
        using Quality = int (*)(int, char**);
        return reinterpret_cast<Quality>(function)(argc - 2, argv + 2);
      });
  }
  std::fprintf(stderr, "tetmesher: unknown command '%s'\n\n%s", command.c_str(), kUsage);
  return 2;
}
