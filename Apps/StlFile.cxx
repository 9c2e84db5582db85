// .stl without VTK, giving what vtkSTLReader with merging gives (SurfaceReaders.cxx): binary
// or ASCII by kwsys's DetectFileType (binary when 5% or more of the first 256 bytes are
// outside printable ASCII, tab, CR and LF); a binary file's facets are read to its end, an
// ASCII file's by vtkSTLReader's grammar (ParseAscii); each facet's 3 vertices are floats,
// merged when they compare equal (as vtkMergePoints does: so -0 and +0 merge, NaN never
// does), numbered in order of first appearance; a facet whose merged vertices are not 3
// distinct points is dropped, its points kept. Anything else (a binary size that is not
// 84 + 50 n bytes, an ASCII file VTK would refuse or that its line buffer would split, a
// big-endian host) is declined and VTK reads it, naming any defect.
#include "SurfaceFiles.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <limits>
#include <unordered_map>
#include <vector>

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

// The facets' corners (9 floats per facet, in file order) merged into `surface`.
void MergeFacets(const std::vector<float>& corners, SurfaceData& surface)
{
  const std::size_t facets = corners.size() / 9;
  surface = SurfaceData();
  surface.points.reserve(3 * facets);
  surface.polygonOffsets.reserve(facets + 1);
  surface.polygonPoints.reserve(3 * facets);
  surface.polygonOffsets.push_back(0);
  std::unordered_map<VertexKey, std::int64_t, VertexKeyHash> ids;
  ids.reserve(facets);
  for (std::size_t f = 0; f < facets; ++f)
  {
    std::int64_t corner[3];
    for (int v = 0; v < 3; ++v)
    {
      const float* xyz = &corners[9 * f + 3 * static_cast<std::size_t>(v)];
      const std::int64_t next = surface.PointCount();
      std::int64_t id = next;
      if (xyz[0] == xyz[0] && xyz[1] == xyz[1] && xyz[2] == xyz[2]) // no NaN
      {
        const VertexKey key{ xyz[0] + 0.0f, xyz[1] + 0.0f, xyz[2] + 0.0f }; // -0 -> +0
        id = ids.emplace(key, next).first->second;
      }
      if (id == next)
        for (int k = 0; k < 3; ++k)
          surface.points.push_back(static_cast<double>(xyz[k]));
      corner[v] = id;
    }
    if (corner[0] != corner[1] && corner[0] != corner[2] && corner[1] != corner[2])
    {
      surface.polygonPoints.insert(surface.polygonPoints.end(), corner, corner + 3);
      surface.polygonOffsets.push_back(static_cast<std::int64_t>(surface.polygonPoints.size()));
    }
  }
}

bool ParseBinary(const unsigned char* data, std::size_t size, std::vector<float>& corners)
{
  constexpr std::size_t kHeader = 84, kFacet = 50;
  if (!LittleEndianHost() || size < kHeader || (size - kHeader) % kFacet != 0)
    return false;
  // vtkSTLReader reads facets to the end of the file, whatever the stored count says.
  const std::size_t facets = (size - kHeader) / kFacet;
  corners.resize(9 * facets);
  for (std::size_t f = 0; f < facets; ++f)
    std::memcpy(&corners[9 * f], data + kHeader + f * kFacet + 12, 36); // after the normal
  return true;
}

// value rounded to float as the hardware rounds (to nearest, ties to even), beyond FLT_MAX
// too, where a plain cast is undefined behaviour.
float RoundToFloat(double value)
{
  const double magnitude = std::fabs(value);
  constexpr double kMax = std::numeric_limits<float>::max();
  constexpr double kHalfUlpAboveMax = 0x1p103; // FLT_MAX's ulp is 2^104
  if (magnitude >= kMax + kHalfUlpAboveMax)
    return static_cast<float>(std::copysign(std::numeric_limits<double>::infinity(), value));
  if (magnitude > kMax)
    return static_cast<float>(std::copysign(kMax, value));
  return static_cast<float>(value);
}

// The grammar of vtkSTLReader::ReadASCIISTL: "solid" lines, each followed by facets ("facet
// ...", "outer ...", three "vertex x y z", "endloop", "endfacet"; "color" lines allowed
// before a facet) and "endsolid"; blank lines skipped; the first word of a line compared in
// lower case, the rest of it ignored but the vertex coordinates, read with strtod and
// rounded to float. It reads the file with fgets into 255 bytes, so a line of 254 or more
// bytes (or a NUL byte) is declined here rather than imitated; so is any file VTK would
// refuse, for VTK's message.
bool ParseAscii(const std::string& text, std::vector<float>& corners)
{
  if (text.find('\0') != std::string::npos)
    return false;
  enum State
  {
    Solid,
    Facet,
    Loop,
    Vertices,
    EndLoop,
    EndFacet
  };
  // The one-keyword steps: in state `from` the line must start with `word`.
  struct Step
  {
    State from;
    const char* word;
    State to;
  };
  static constexpr Step kSteps[] = { { Solid, "solid", Facet },
    { Loop, "outer", Vertices },
    { EndLoop, "endloop", EndFacet },
    { EndFacet, "endfacet", Facet } };
  State state = Solid;
  bool anySolid = false;
  int vertex = 0;
  std::size_t begin = 0;
  std::string line; // one line, NUL-terminated as fgets leaves it: strtod stops at its end
  std::string word;
  while (begin < text.size())
  {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos)
      end = text.size();
    if (end - begin >= 254)
      return false;
    line.assign(text, begin, end - begin);
    begin = end + 1;
    std::size_t at = 0;
    while (at < line.size() && std::isspace(static_cast<unsigned char>(line[at])))
      ++at;
    if (at == line.size())
      continue;
    std::size_t wordEnd = at;
    word.clear();
    while (wordEnd < line.size() && !std::isspace(static_cast<unsigned char>(line[wordEnd])))
      word += static_cast<char>(std::tolower(static_cast<unsigned char>(line[wordEnd++])));
    if (state == Facet)
    {
      if (word == "facet")
        state = Loop;
      else if (word == "endsolid")
        state = Solid;
      else if (word != "color")
        return false;
    }
    else if (state == Vertices)
    {
      if (word != "vertex")
        return false;
      const char* from = line.c_str() + wordEnd;
      for (int k = 0; k < 3; ++k)
      {
        char* to = nullptr;
        const double value = std::strtod(from, &to);
        if (to == from)
          return false;
        corners.push_back(RoundToFloat(value));
        from = to;
      }
      if (++vertex == 3)
      {
        vertex = 0;
        state = EndLoop;
      }
    }
    else
    {
      const Step* step = std::find_if(
        std::begin(kSteps), std::end(kSteps), [&](const Step& s) { return s.from == state; });
      if (word != step->word)
        return false;
      anySolid = anySolid || state == Solid;
      state = step->to;
    }
  }
  return state == Solid && anySolid;
}

} // namespace

bool ReadStl(const std::string& path, SurfaceData& surface)
{
  std::string bytes;
  if (!ReadWholeFile(path, bytes))
    return false;
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  std::vector<float> corners;
  const bool parsed = DetectedAsBinary(data, bytes.size())
    ? ParseBinary(data, bytes.size(), corners)
    : ParseAscii(bytes, corners);
  if (!parsed)
    return false;
  MergeFacets(corners, surface);
  return true;
}

} // namespace cli
} // namespace tetmesher
