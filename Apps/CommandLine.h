// The subcommands of `tetmesher`. Each takes the arguments after its name and returns the
// process exit status (0 ok, 1 bad input or failure, 2 wrong usage).
#pragma once

namespace tetmesher
{
namespace cli
{
int RunQuality(int argc, char* argv[]);
int RunMesh(int argc, char* argv[]);
} // namespace cli
} // namespace tetmesher
