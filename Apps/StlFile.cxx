// Binary .stl without VTK, giving what vtkSTLReader with merging gives (SurfaceReaders.cxx):
// the file is binary by kwsys's DetectFileType (5% or more of its first 256 bytes outside
// printable ASCII, tab, CR and LF); each facet's 3 vertices are floats, merged when they
// compare equal (as vtkMergePoints does: so -0 and +0 merge, NaN never does), numbered in
// order of first appearance; a facet whose merged vertices are not 3 distinct points is
// dropped, its points kept. Anything else (ASCII, a size that is not 84 + 50 n bytes, a
// big-endian host) is declined and VTK reads it, naming any defect.
#include "SurfaceFiles.h"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <unordered_map>

namespace tetmesher
{
namespace cli
{

namespace
{

// kwsys::SystemTools::DetectFileType with its defaults (256 bytes, 5%).
bool DetectedAsBinary(const unsigned char* bytes, std::size_t size)
{
  const std::size_t length = size < 256 ? size : 256;
  if (length == 0)
    return false; // "unknown": VTK then tries binary and reports the missing header
  std::size_t text = 0;
  for (std::size_t i = 0; i < length; ++i)
  {
    const unsigned char c = bytes[i];
    if ((c >= 0x20 && c <= 0x7F) || c == '\n' || c == '\r' || c == '\t')
      ++text;
  }
  return static_cast<double>(length - text) / static_cast<double>(length) >= 0.05;
}

bool LittleEndianHost()
{
  const std::uint32_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

// A vertex as the merge compares it: the three floats, with -0 read as +0 (they compare
// equal). NaN coordinates never reach the table.
struct VertexKey
{
  float x, y, z;
  bool operator==(const VertexKey& o) const { return x == o.x && y == o.y && z == o.z; }
};

struct VertexKeyHash
{
  std::size_t operator()(const VertexKey& k) const
  {
    std::uint32_t bits[3];
    std::memcpy(&bits[0], &k.x, 4);
    std::memcpy(&bits[1], &k.y, 4);
    std::memcpy(&bits[2], &k.z, 4);
    std::uint64_t h = 0x9E3779B97F4A7C15ULL;
    for (std::uint32_t b : bits)
      h = (h ^ b) * 0xBF58476D1CE4E5B9ULL;
    return static_cast<std::size_t>(h ^ (h >> 31));
  }
};

} // namespace

bool ReadBinaryStl(const std::string& path, SurfaceData& surface)
{
  std::string bytes;
  if (!LittleEndianHost() || !ReadWholeFile(path, bytes))
    return false;
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const std::size_t size = bytes.size();
  constexpr std::size_t kHeader = 84, kFacet = 50;
  if (!DetectedAsBinary(data, size) || size < kHeader || (size - kHeader) % kFacet != 0)
    return false;
  // vtkSTLReader reads facets to the end of the file, whatever the stored count says.
  const std::size_t facets = (size - kHeader) / kFacet;

  surface = SurfaceData();
  surface.points.reserve(3 * facets);
  surface.polygonOffsets.reserve(facets + 1);
  surface.polygonPoints.reserve(3 * facets);
  surface.polygonOffsets.push_back(0);
  std::unordered_map<VertexKey, std::int64_t, VertexKeyHash> ids;
  ids.reserve(facets);
  for (std::size_t f = 0; f < facets; ++f)
  {
    const unsigned char* facet = data + kHeader + f * kFacet;
    std::int64_t corner[3];
    for (int v = 0; v < 3; ++v)
    {
      float xyz[3];
      std::memcpy(xyz, facet + 12 * (v + 1), 12); // after the normal
      const std::int64_t next = surface.PointCount();
      std::int64_t id = next;
      if (xyz[0] == xyz[0] && xyz[1] == xyz[1] && xyz[2] == xyz[2]) // no NaN
      {
        const VertexKey key{ xyz[0] + 0.0f, xyz[1] + 0.0f, xyz[2] + 0.0f }; // -0 -> +0
        id = ids.emplace(key, next).first->second;
      }
      if (id == next)
        for (float c : xyz)
          surface.points.push_back(static_cast<double>(c));
      corner[v] = id;
    }
    if (corner[0] != corner[1] && corner[0] != corner[2] && corner[1] != corner[2])
    {
      surface.polygonPoints.insert(surface.polygonPoints.end(), corner, corner + 3);
      surface.polygonOffsets.push_back(static_cast<std::int64_t>(surface.polygonPoints.size()));
    }
  }
  return true;
}

} // namespace cli
} // namespace tetmesher
