#include "MeshExport.h"

#include "SurfaceFiles.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <unordered_set>
#include <vector>

namespace tetmesher
{
namespace cli
{
namespace
{

// The face opposite point i of a positive VTK tet, its vertices ordered so that the
// right-hand normal points out of the tet.
constexpr int kOutwardFace[4][3] = { { 1, 2, 3 }, { 0, 3, 2 }, { 0, 1, 3 }, { 0, 2, 1 } };

// A file written through a buffer; errors name the file.
class TextFile
{
public:
  explicit TextFile(const std::string& path)
    : path_(path)
    , file_(std::fopen(path.c_str(), "wb"))
  {
    if (!file_)
      Fail(path, std::string("could not be written (") + std::strerror(errno) + ")");
    buffer_.reserve(kFlushAt + 256);
  }
  ~TextFile()
  {
    if (file_)
      std::fclose(file_);
  }
  TextFile(const TextFile&) = delete;
  TextFile& operator=(const TextFile&) = delete;

  TextFile& operator<<(const char* text)
  {
    buffer_ += text;
    return Flushed();
  }
  TextFile& operator<<(char c)
  {
    buffer_ += c;
    return Flushed();
  }
  TextFile& operator<<(std::int64_t value)
  {
    char digits[24];
    const auto end = std::to_chars(digits, digits + sizeof digits, value).ptr;
    buffer_.append(digits, end);
    return Flushed();
  }
  // The shortest text that reads back to the same double.
  TextFile& operator<<(double value)
  {
    char digits[32];
    const auto end = std::to_chars(digits, digits + sizeof digits, value).ptr;
    buffer_.append(digits, end);
    return Flushed();
  }

  void Close()
  {
    Flush();
    const bool failed = std::ferror(file_) != 0;
    const bool closeFailed = std::fclose(file_) != 0;
    file_ = nullptr;
    if (failed || closeFailed)
      Fail(path_, "could not be written completely (disk full?)");
  }

private:
  static constexpr std::size_t kFlushAt = std::size_t(1) << 20;
  TextFile& Flushed()
  {
    if (buffer_.size() >= kFlushAt)
      Flush();
    return *this;
  }
  void Flush()
  {
    if (!buffer_.empty() && std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size())
      Fail(path_, "could not be written completely (disk full?)");
    buffer_.clear();
  }

  std::string path_;
  std::FILE* file_;
  std::string buffer_;
};

struct BoundaryTriangle
{
  std::int64_t v[3];
  std::int64_t inputCell;
};

struct TripleHash
{
  std::size_t operator()(const std::array<std::int64_t, 3>& k) const
  {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (std::int64_t v : k)
      h = (h ^ static_cast<std::uint64_t>(v)) * 0x100000001b3ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

// Every face on an input triangle, once, oriented out of the first tet that has it.
std::vector<BoundaryTriangle> BoundaryTriangles(const ExportMesh& mesh)
{
  std::vector<BoundaryTriangle> triangles;
  if (!mesh.inputFaceIds)
    return triangles;
  std::unordered_set<std::array<std::int64_t, 3>, TripleHash> seen;
  for (std::int64_t t = 0; t < mesh.tetCount; ++t)
    for (int i = 0; i < 4; ++i)
    {
      const std::int64_t cell = mesh.inputFaceIds[4 * t + i];
      if (cell < 0)
        continue;
      BoundaryTriangle triangle;
      for (int k = 0; k < 3; ++k)
        triangle.v[k] = mesh.cells[4 * t + kOutwardFace[i][k]];
      triangle.inputCell = cell;
      std::array<std::int64_t, 3> key = { triangle.v[0], triangle.v[1], triangle.v[2] };
      std::sort(key.begin(), key.end());
      if (seen.insert(key).second)
        triangles.push_back(triangle);
    }
  return triangles;
}

std::int64_t RegionOf(const ExportMesh& mesh, std::int64_t t)
{
  return mesh.regionIds ? mesh.regionIds[t] : 0;
}

// Whether every region attribute is a whole number in [lowest, 2^31 - 1]: Gmsh's physical
// tags are positive, Medit's references any int.
bool AttributesAreTags(const ExportMesh& mesh, double lowest = 1)
{
  if (!mesh.regionAttribute)
    return false;
  for (std::int64_t t = 0; t < mesh.tetCount; ++t)
  {
    const double a = mesh.regionAttribute[t];
    if (!(a >= lowest && a <= 2147483647.0 && a == std::floor(a)))
      return false;
  }
  return true;
}

void WriteGmsh22(const ExportMesh& mesh, const std::string& path)
{
  const bool attributeTags = AttributesAreTags(mesh);
  const std::vector<BoundaryTriangle> triangles = BoundaryTriangles(mesh);
  TextFile out(path);
  out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" << mesh.pointCount << '\n';
  for (std::int64_t p = 0; p < mesh.pointCount; ++p)
  {
    const double* x = mesh.points + 3 * p;
    out << p + 1 << ' ' << x[0] << ' ' << x[1] << ' ' << x[2] << '\n';
  }
  out << "$EndNodes\n$Elements\n"
      << static_cast<std::int64_t>(triangles.size()) + mesh.tetCount << '\n';
  std::int64_t element = 0;
  for (const BoundaryTriangle& triangle : triangles)
  {
    out << ++element << " 2 2 1 " << triangle.inputCell + 1;
    for (std::int64_t v : triangle.v)
      out << ' ' << v + 1;
    out << '\n';
  }
  for (std::int64_t t = 0; t < mesh.tetCount; ++t)
  {
    const std::int64_t tag = RegionOf(mesh, t) + 1;
    const std::int64_t physical =
      attributeTags ? static_cast<std::int64_t>(mesh.regionAttribute[t]) : tag;
    out << ++element << " 4 2 " << physical << ' ' << tag;
    for (int i = 0; i < 4; ++i)
      out << ' ' << mesh.cells[4 * t + i] + 1;
    out << '\n';
  }
  out << "$EndElements\n";
  out.Close();
}

void WriteTetGen(const ExportMesh& mesh, const std::string& path)
{
  const std::string name = path.substr(0, path.size() - LowerExtension(path).size());
  {
    TextFile node(name + ".node");
    node << mesh.pointCount << " 3 0 0\n";
    for (std::int64_t p = 0; p < mesh.pointCount; ++p)
    {
      const double* x = mesh.points + 3 * p;
      node << p << ' ' << x[0] << ' ' << x[1] << ' ' << x[2] << '\n';
    }
    node.Close();
  }
  {
    TextFile ele(name + ".ele");
    ele << mesh.tetCount << " 4 1\n";
    for (std::int64_t t = 0; t < mesh.tetCount; ++t)
    {
      ele << t;
      for (int i = 0; i < 4; ++i)
        ele << ' ' << mesh.cells[4 * t + i];
      if (mesh.regionAttribute)
        ele << ' ' << mesh.regionAttribute[t] << '\n';
      else
        ele << ' ' << RegionOf(mesh, t) << '\n';
    }
    ele.Close();
  }
  const std::vector<BoundaryTriangle> triangles = BoundaryTriangles(mesh);
  TextFile face(name + ".face");
  face << static_cast<std::int64_t>(triangles.size()) << " 1\n";
  std::int64_t index = 0;
  for (const BoundaryTriangle& triangle : triangles)
  {
    face << index++;
    for (std::int64_t v : triangle.v)
      face << ' ' << v;
    face << ' ' << triangle.inputCell + 1 << '\n';
  }
  face.Close();
}

void WriteMedit(const ExportMesh& mesh, const std::string& path)
{
  const bool attributeRefs = AttributesAreTags(mesh, -2147483648.0);
  const std::vector<BoundaryTriangle> triangles = BoundaryTriangles(mesh);
  TextFile out(path);
  out << "MeshVersionFormatted 2\nDimension 3\nVertices\n" << mesh.pointCount << '\n';
  for (std::int64_t p = 0; p < mesh.pointCount; ++p)
  {
    const double* x = mesh.points + 3 * p;
    out << x[0] << ' ' << x[1] << ' ' << x[2] << " 0\n";
  }
  out << "Tetrahedra\n" << mesh.tetCount << '\n';
  for (std::int64_t t = 0; t < mesh.tetCount; ++t)
  {
    for (int i = 0; i < 4; ++i)
      out << mesh.cells[4 * t + i] + 1 << ' ';
    out << (attributeRefs ? static_cast<std::int64_t>(mesh.regionAttribute[t])
                          : RegionOf(mesh, t) + 1)
        << '\n';
  }
  if (!triangles.empty())
  {
    out << "Triangles\n" << static_cast<std::int64_t>(triangles.size()) << '\n';
    for (const BoundaryTriangle& triangle : triangles)
    {
      for (std::int64_t v : triangle.v)
        out << v + 1 << ' ';
      out << triangle.inputCell + 1 << '\n';
    }
  }
  out << "End\n";
  out.Close();
}

} // namespace

bool IsExportExtension(const std::string& lowerExtension)
{
  return lowerExtension == ".msh" || lowerExtension == ".node" || lowerExtension == ".ele" ||
    lowerExtension == ".mesh";
}

void WriteExportMesh(const ExportMesh& mesh, const std::string& path)
{
  const std::string ext = LowerExtension(path);
  if (ext == ".msh")
    WriteGmsh22(mesh, path);
  else if (ext == ".node" || ext == ".ele")
    WriteTetGen(mesh, path);
  else if (ext == ".mesh")
    WriteMedit(mesh, path);
  else
    Fail(path, "unknown output type '" + ext + "' (use .vtu, .vtk, .msh, .mesh, .node or .ele)");
}

} // namespace cli
} // namespace tetmesher
