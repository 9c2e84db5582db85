#include "GmshFile.h"

#include "SurfaceFiles.h"

#include <sstream>
#include <unordered_map>

namespace tetmesher
{
namespace cli
{

GmshMesh ReadGmshMesh(const std::string& path, const GmshElementFilter& keep)
{
  RequireReadableFile(path);
  TokenFile file(path);
  std::istringstream line;
  std::string token;
  double version = 0;
  GmshMesh mesh;
  std::unordered_map<long, std::int64_t> idOfTag;
  std::vector<long> nodeTags; // of the kept elements' nodes, resolved at the end
  bool nodesRead = false;

  auto addNode = [&](long tag, double x, double y, double z)
  {
    if (!idOfTag.emplace(tag, static_cast<std::int64_t>(mesh.points.size() / 3)).second)
      file.Fail("node " + std::to_string(tag) + " is defined twice");
    mesh.points.insert(mesh.points.end(), { x, y, z });
  };
  // An element of `type` with its node tags next in `line`; element `tag` for messages.
  auto addElement = [&](long tag, long type)
  {
    std::string refusal;
    const int corners = keep(type, refusal);
    if (!refusal.empty())
      file.Fail("element " + std::to_string(tag) + " " + refusal);
    if (corners <= 0)
      return;
    for (int k = 0; k < corners; ++k)
    {
      long node;
      if (!(line >> node))
        file.Fail("element " + std::to_string(tag) + ": expected " + std::to_string(corners) +
          " node tags");
      nodeTags.push_back(node);
    }
    mesh.offsets.push_back(static_cast<std::int64_t>(nodeTags.size()));
    mesh.types.push_back(type);
    mesh.tags.push_back(tag);
  };

  while (file.NextLine(line))
  {
    if (!(line >> token) || token[0] != '$' || token.compare(0, 4, "$End") == 0)
      continue; // the body of a section this reader skips
    if (token == "$MeshFormat")
    {
      int fileType = 0;
      if (!file.NextLine(line) || !(line >> version >> fileType))
        file.Fail("expected 'version file-type data-size' after $MeshFormat");
      if (fileType != 0)
        file.Fail("binary .msh files are not supported; save as ASCII (Gmsh: -format msh2 or "
                  "msh41 with Mesh.Binary=0)");
      if (!(version >= 2 && version < 3) && version != 4.1)
      {
        std::ostringstream text;
        text << "unsupported .msh version " << version
             << " (read: 2.2 and 4.1 ASCII; Gmsh: -format msh22 or msh41)";
        file.Fail(text.str());
      }
    }
    else if (token == "$Nodes" || (token == "$ParametricNodes" && version < 3))
    {
      if (version == 0)
        file.Fail("$Nodes before $MeshFormat");
      if (version < 3)
      {
        long n;
        if (!file.NextLine(line) || !(line >> n) || n < 0)
          file.Fail("expected the node count");
        mesh.points.reserve(3 * ReserveBound(n));
        for (long i = 0; i < n; ++i)
        {
          long tag;
          double x, y, z;
          if (!file.NextLine(line) || !(line >> tag >> x >> y >> z))
            file.Fail("expected node " + std::to_string(i + 1) + " of " + std::to_string(n) +
              " as 'tag x y z'");
          addNode(tag, x, y, z);
        }
      }
      else
      {
        long blocks, n, minTag, maxTag;
        if (!file.NextLine(line) || !(line >> blocks >> n >> minTag >> maxTag) || n < 0)
          file.Fail("expected 'numEntityBlocks numNodes minNodeTag maxNodeTag'");
        mesh.points.reserve(3 * ReserveBound(n));
        for (long b = 0; b < blocks; ++b)
        {
          long dim, entity, parametric, inBlock;
          if (!file.NextLine(line) || !(line >> dim >> entity >> parametric >> inBlock) ||
            inBlock < 0)
            file.Fail("expected a node block's 'entityDim entityTag parametric numNodesInBlock'");
          std::vector<long> blockTags;
          blockTags.reserve(ReserveBound(inBlock));
          for (long i = 0; i < inBlock; ++i)
          {
            long tag;
            if (!file.NextLine(line) || !(line >> tag))
              file.Fail("expected a node tag");
            blockTags.push_back(tag);
          }
          // Parametric coordinates, when present, follow x y z on the line: not read.
          for (long i = 0; i < inBlock; ++i)
          {
            double x, y, z;
            if (!file.NextLine(line) || !(line >> x >> y >> z))
              file.Fail("expected the coordinates 'x y z' of node " +
                std::to_string(blockTags[static_cast<std::size_t>(i)]));
            addNode(blockTags[static_cast<std::size_t>(i)], x, y, z);
          }
        }
      }
      nodesRead = true;
    }
    else if (token == "$Elements")
    {
      if (!nodesRead)
        file.Fail("$Elements before $Nodes");
      if (version < 3)
      {
        long n;
        if (!file.NextLine(line) || !(line >> n) || n < 0)
          file.Fail("expected the element count");
        for (long i = 0; i < n; ++i)
        {
          long tag, type, tagCount;
          if (!file.NextLine(line) || !(line >> tag >> type >> tagCount) || tagCount < 0)
            file.Fail("expected element " + std::to_string(i + 1) + " of " + std::to_string(n) +
              " as 'tag type numTags tags... nodes...'");
          long skip;
          for (long k = 0; k < tagCount; ++k)
            if (!(line >> skip))
              file.Fail("element " + std::to_string(tag) + ": expected " +
                std::to_string(tagCount) + " tags");
          addElement(tag, type);
        }
      }
      else
      {
        long blocks, n, minTag, maxTag;
        if (!file.NextLine(line) || !(line >> blocks >> n >> minTag >> maxTag))
          file.Fail("expected 'numEntityBlocks numElements minElementTag maxElementTag'");
        for (long b = 0; b < blocks; ++b)
        {
          long dim, entity, type, inBlock;
          if (!file.NextLine(line) || !(line >> dim >> entity >> type >> inBlock) || inBlock < 0)
            file.Fail("expected an element block's 'entityDim entityTag elementType "
                      "numElementsInBlock'");
          for (long i = 0; i < inBlock; ++i)
          {
            long tag;
            if (!file.NextLine(line) || !(line >> tag))
              file.Fail("expected an element 'tag nodes...'");
            addElement(tag, type);
          }
        }
      }
    }
  }
  if (version == 0)
    Fail(path, "not a Gmsh .msh file (no $MeshFormat section)");
  mesh.nodes.reserve(nodeTags.size());
  for (std::size_t i = 0, element = 0; i < nodeTags.size(); ++i)
  {
    while (static_cast<std::int64_t>(i) >= mesh.offsets[element + 1])
      ++element;
    const auto found = idOfTag.find(nodeTags[i]);
    if (found == idOfTag.end())
      Fail(path,
        "element " + std::to_string(mesh.tags[element]) + " uses undefined node " +
          std::to_string(nodeTags[i]));
    mesh.nodes.push_back(found->second);
  }
  return mesh;
}

} // namespace cli
} // namespace tetmesher
