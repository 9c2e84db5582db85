#include "InstallLayout.h"

#include <unistd.h>

namespace tetmesher
{
namespace cli
{

std::string PathBesideExecutable(const std::string& dir, const char* fileName)
{
  if (!dir.empty() && dir[0] == '/')
    return dir + "/" + fileName;
  char self[4096];
  const ssize_t length = readlink("/proc/self/exe", self, sizeof(self) - 1);
  if (length <= 0)
    return std::string();
  const std::string exe(self, static_cast<std::size_t>(length));
  return exe.substr(0, exe.find_last_of('/') + 1) + dir + "/" + fileName;
}

} // namespace cli
} // namespace tetmesher
