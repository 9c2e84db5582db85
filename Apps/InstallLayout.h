// Where tetmesher's parts lie relative to the running executable: its modules in the library
// directory (bin/../lib), and, for the static executable, its dynamic twin (bin/../libexec).
// Found through /proc/self/exe, so that the build tree and any install prefix work alike.
#pragma once

#include <string>

namespace tetmesher
{
namespace cli
{

// dir/fileName when dir is absolute, else the executable's directory/dir/fileName; empty when
// the executable's path cannot be read.
std::string PathBesideExecutable(const std::string& dir, const char* fileName);

} // namespace cli
} // namespace tetmesher
