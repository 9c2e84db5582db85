#include "MeditFile.h"

#include "SurfaceFiles.h"

#include <cerrno>
#include <cstdlib>
#include <sstream>
#include <type_traits>

namespace tetmesher
{
namespace cli
{
namespace
{

// The tokens of a file whose lines carry no meaning (Medit's): TokenFile's lines, comments cut.
class Tokens
{
public:
  explicit Tokens(const std::string& path)
    : file_(path)
  {
  }

  bool Next(std::string& token)
  {
    while (!(line_ >> token))
      if (!file_.NextLine(line_))
        return false;
    return true;
  }
  // The next token as a number; `what()` names it in the message when there is none.
  template<typename Number, typename What>
  void Expect(Number& value, const What& what)
  {
    if (!Next(token_))
      Fail("the file ends where " + std::string(what()) + " was expected");
    const char* begin = token_.c_str();
    char* end = nullptr;
    errno = 0;
    if constexpr (std::is_floating_point_v<Number>)
      value = std::strtod(begin, &end);
    else
    {
      const long number = std::strtol(begin, &end, 10);
      value = static_cast<Number>(number);
      if (static_cast<long>(value) != number)
        errno = ERANGE;
    }
    if (end == begin || *end != '\0' || (errno == ERANGE && !std::is_floating_point_v<Number>))
      Fail("expected " + std::string(what()) + ", read '" + token_ + "'");
  }
  [[noreturn]] void Fail(const std::string& what) const { file_.Fail(what); }

private:
  TokenFile file_;
  std::istringstream line_;
  std::string token_;
};

// Sections skipped: the numbers per entity that follow their count.
int SkippedSize(const std::string& keyword)
{
  static const std::pair<const char*, int> kSizes[] = { { "edges", 3 },
    { "hexahedra", 9 },
    { "prisms", 7 },
    { "pyramids", 6 },
    { "corners", 1 },
    { "requiredvertices", 1 },
    { "ridges", 1 },
    { "requirededges", 1 },
    { "requiredtriangles", 1 },
    { "requiredquadrilaterals", 1 },
    { "requiredtetrahedra", 1 },
    { "normals", 3 },
    { "normalatvertices", 2 },
    { "normalattrianglevertices", 3 },
    { "tangents", 3 },
    { "tangentatvertices", 2 },
    { "tangentatedgevertices", 3 },
    { "edgesp2", 4 },
    { "tetrahedrap2", 11 } };
  for (const auto& [name, size] : kSizes)
    if (keyword == name)
      return size;
  return 0;
}

} // namespace

MeditMesh ReadMeditMesh(const std::string& path)
{
  RequireReadableFile(path);
  Tokens in(path);
  MeditMesh mesh;
  std::string token;
  bool versionRead = false;
  // Ids from 1 as written, checked once every vertex is known (the sections may come in any
  // order); each section's start, to name an element by its number in its section.
  struct Section
  {
    bool surface;
    int corners;
    const char* singular;
    std::size_t firstId; // in polygonPoints or tetrahedra
  };
  std::vector<Section> sections;
  auto count = [&](const std::string& name)
  {
    long n = 0;
    in.Expect(n, [&] { return "the number of " + name; });
    if (n < 0)
      in.Fail("a negative number of " + name);
    return n;
  };
  while (in.Next(token))
  {
    const std::string keyword = LowerCase(token);
    if (keyword == "meshversionformatted")
    {
      int version = 0;
      in.Expect(version, [] { return "the version after MeshVersionFormatted"; });
      versionRead = true;
    }
    else if (!versionRead)
      in.Fail("not a Medit .mesh file (it starts with '" + token + "', not MeshVersionFormatted)");
    else if (keyword == "dimension")
    {
      int dimension = 0;
      in.Expect(dimension, [] { return "the dimension"; });
      if (dimension != 3)
        in.Fail("a " + std::to_string(dimension) +
          "D mesh: tetmesher meshes closed surfaces in 3D (Dimension 3)");
    }
    else if (keyword == "vertices")
    {
      const long n = count("vertices");
      mesh.points.reserve(mesh.points.size() + 3 * ReserveBound(n));
      for (long i = 0; i < n; ++i)
      {
        double x[3];
        for (int k = 0; k < 3; ++k)
          in.Expect(x[k],
            [&]
            {
              return std::string("the ") + "xyz"[k] + " of vertex " + std::to_string(i + 1) +
                " of " + std::to_string(n);
            });
        long ref;
        in.Expect(ref,
          [&] {
            return "the reference of vertex " + std::to_string(i + 1) + " of " + std::to_string(n);
          });
        mesh.points.insert(mesh.points.end(), x, x + 3);
      }
    }
    else if (keyword == "triangles" || keyword == "quadrilaterals" || keyword == "tetrahedra")
    {
      const int corners = keyword == "triangles" ? 3 : 4;
      const bool surface = keyword != "tetrahedra";
      const char* singular = keyword == "triangles" ? "triangle"
        : surface                                   ? "quadrilateral"
                                                    : "tetrahedron";
      const long n = count(keyword);
      sections.push_back(
        { surface, corners, singular, (surface ? mesh.polygonPoints : mesh.tetrahedra).size() });
      for (long i = 0; i < n; ++i)
      {
        auto which = [&] {
          return std::string(singular) + " " + std::to_string(i + 1) + " of " + std::to_string(n);
        };
        for (int k = 0; k < corners; ++k)
        {
          long id;
          in.Expect(id, [&] { return "vertex " + std::to_string(k + 1) + " of " + which(); });
          // Kept from 1 until every vertex is read; 0 and negatives fail below.
          (surface ? mesh.polygonPoints : mesh.tetrahedra).push_back(id);
        }
        long ref;
        in.Expect(ref, [&] { return "the reference of " + which(); });
        if (surface)
          mesh.polygonOffsets.push_back(static_cast<std::int64_t>(mesh.polygonPoints.size()));
        else
          mesh.tetrahedronRefs.push_back(ref);
      }
    }
    else if (keyword == "trianglesp2" || keyword == "quadrilateralsq2")
      in.Fail("second-order (curved) " +
        std::string(keyword == "trianglesp2" ? "triangles" : "quadrilaterals") + " (" + token +
        "): save the surface with first-order elements");
    else if (keyword == "end")
      break;
    else if (keyword == "identifier" || keyword == "geometry")
      in.Next(token); // a name
    else if (const int size = SkippedSize(keyword))
    {
      const long n = count(keyword);
      for (long i = 0; i < n; ++i) // (size * n could overflow on a corrupt count)
        for (int k = 0; k < size; ++k)
          if (!in.Next(token))
            in.Fail("the file ends inside the " + std::string(keyword) + " section");
    }
    else
      in.Fail("unknown keyword '" + token + "'");
  }
  if (!versionRead)
    Fail(path, "not a Medit .mesh file (no MeshVersionFormatted)");
  // The ids from 1, checked against the vertices now known.
  const auto vertexCount = static_cast<std::int64_t>(mesh.points.size() / 3);
  auto resolve = [&](std::vector<std::int64_t>& ids, bool surface)
  {
    for (std::size_t i = 0; i < ids.size(); ++i)
    {
      if (ids[i] >= 1 && ids[i] <= vertexCount)
      {
        --ids[i];
        continue;
      }
      // Named by its section and its number there.
      const Section* section = nullptr;
      for (const Section& candidate : sections)
        if (candidate.surface == surface && candidate.firstId <= i)
          section = &candidate;
      const std::size_t element =
        (i - section->firstId) / static_cast<std::size_t>(section->corners);
      const std::string name = section->singular;
      Fail(path,
        name + " " + std::to_string(element + 1) + " uses vertex " + std::to_string(ids[i]) +
          ", not among the " + std::to_string(vertexCount) + " vertices (numbered from 1)");
    }
  };
  resolve(mesh.polygonPoints, true);
  resolve(mesh.tetrahedra, false);
  return mesh;
}

} // namespace cli
} // namespace tetmesher
