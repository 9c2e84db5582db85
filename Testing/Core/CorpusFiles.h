// The surfaces of the repository's Data/ folder, for tests that mesh real models.
#pragma once

#include "SurfaceGenerators.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace tetmesher
{
namespace testing
{

// Minimal .off reader for the Data/ corpus (counts on the header line or the next one,
// polygons as fans); coordinates are read with full double precision.
inline bool readCorpusOff(const std::string& name, Surface& s)
{
  const std::filesystem::path path =
    std::filesystem::path(__FILE__).parent_path().parent_path().parent_path() / "Data" / name;
  std::ifstream in(path);
  std::string header;
  long nv = 0, nf = 0, ne = 0;
  if (!(in >> header) || header.find("OFF") == std::string::npos || !(in >> nv >> nf >> ne))
    return false;
  for (long v = 0; v < nv; ++v)
  {
    double x, y, z;
    if (!(in >> x >> y >> z))
      return false;
    s.addPoint(x, y, z);
  }
  for (long f = 0; f < nf; ++f)
  {
    int n = 0;
    in >> n;
    std::vector<std::int32_t> ids(n);
    for (auto& id : ids)
      in >> id;
    if (!in || n < 3)
      return false;
    for (int k = 1; k + 1 < n; ++k)
      s.addTriangle(ids[0], ids[k], ids[k + 1]);
  }
  return true;
}

} // namespace testing
} // namespace tetmesher
