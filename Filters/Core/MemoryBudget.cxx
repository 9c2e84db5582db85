#include "MemoryBudget.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#if defined(__unix__) || defined(__APPLE__)
#include <sys/resource.h>
#include <unistd.h>
#endif

namespace tetmesher
{

double availableMemoryBytes()
{
  double available = 0;
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double value = 0;
  std::string unit;
  while (meminfo >> key >> value)
  {
    std::getline(meminfo, unit);
    if (key == "MemAvailable:")
    {
      available = value * 1024.0; // the file says kB and means KiB
      break;
    }
  }
#if defined(_SC_AVPHYS_PAGES) && defined(_SC_PAGESIZE)
  if (available <= 0)
  {
    const long pages = sysconf(_SC_AVPHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
    if (pages > 0 && pageSize > 0)
      available = static_cast<double>(pages) * static_cast<double>(pageSize);
  }
#endif
#if defined(__unix__) || defined(__APPLE__)
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
  {
    const double addressSpace = static_cast<double>(limit.rlim_cur);
    if (available <= 0 || addressSpace < available)
      available = addressSpace;
  }
#endif
  return available;
}

std::string formatBytes(double bytes)
{
  const char* units[] = { "bytes", "kB", "MB", "GB", "TB", "PB" };
  int unit = 0;
  while (bytes >= 1000.0 && unit < 5)
  {
    bytes /= 1000.0;
    ++unit;
  }
  char text[64];
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.3g %s", bytes, units[unit]);
  return text;
}

namespace
{
// Empty when `points` vertices (about kTetsPerPoint tets each, `bytesPerPoint` bytes) fit;
// else `what` followed by the estimate, the limit exceeded and `remedy`.
std::string checkBudget(double points,
  double bytesPerPoint,
  double limitBytes,
  const std::string& what,
  const char* remedy)
{
  const double tets = points * kTetsPerPoint;
  const double bytes = points * bytesPerPoint;
  const bool tooManyTets = !(tets <= kMaxTets);
  const bool tooMuchMemory = limitBytes > 0 && !(bytes <= limitBytes);
  if (!tooManyTets && !tooMuchMemory)
    return "";
  std::ostringstream message;
  message.precision(3);
  message << what << " about " << tets << " tetrahedra and " << formatBytes(bytes)
          << " of memory, ";
  if (tooManyTets)
    message << "more than the " << kMaxTets << " tetrahedra a mesh can have";
  else
    message << "more than the memory limit of " << formatBytes(limitBytes);
  message << "; " << remedy;
  return message.str();
}

std::string count(double value)
{
  std::ostringstream text;
  text.precision(3);
  text << value;
  return text.str();
}
} // namespace

std::string checkMemoryBudget(double estimatedPoints, double limitBytes)
{
  return checkBudget(estimatedPoints,
    kBytesPerEstimatedPoint,
    limitBytes,
    "the size field asks for about " + count(estimatedPoints) + " interior points:",
    "ask for larger elements (a larger size, size scale or minimum size)");
}

std::string checkBoundaryMemoryBudget(double pointCount, double limitBytes)
{
  return checkBudget(pointCount,
    kBytesPerInputPoint,
    limitBytes,
    "the surface has " + count(pointCount) + " points: its boundary mesh needs",
    "mesh a coarser surface (decimate it) or split it into parts");
}

} // namespace tetmesher
