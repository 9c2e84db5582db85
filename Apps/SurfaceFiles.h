// The files of the common `tetmesher mesh` run, without VTK: .off, .stl and VTK XML .vtp
// surfaces in, a VTK XML .vtu (appended raw binary, optionally zlib) out. The .vtp reader
// takes the encodings VTK writes (ascii, base64 binary, appended raw or base64; zlib or no
// compression; little-endian) and declines the rest, which VTK then reads (MeshFiles.cxx).
#pragma once

#include <cstdint>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace tetmesher
{
struct SurfaceMeshOutput;

namespace cli
{

// A defect in an input file: the message names the file and what is wrong.
struct FileError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

[[noreturn]] void Fail(const std::string& path, const std::string& what);

// Throws FileError unless `path` is a non-empty regular file that can be opened.
void RequireReadableFile(const std::string& path);

// ".vtu" for "a/b.VTU"; "" without an extension.
std::string LowerExtension(const std::string& path);

// `text` in lower case (ASCII), e.g. a keyword read case-insensitively.
std::string LowerCase(std::string text);

// The whole file as bytes; false when it cannot be read.
bool ReadWholeFile(const std::string& path, std::string& bytes);

// What to reserve for `count` items read from a file's header: the count, up to a bound, so
// that the count of a corrupt header gives its error rather than bad_alloc.
inline std::size_t ReserveBound(long count)
{
  return static_cast<std::size_t>(count < 0 ? 0 : count < (1L << 24) ? count : (1L << 24));
}

// A line-oriented tokenizer that skips '#' comments and knows the line number for errors.
class TokenFile
{
public:
  explicit TokenFile(const std::string& path);
  bool NextLine(std::istringstream& line);
  [[noreturn]] void Fail(const std::string& what) const;

private:
  std::string Path;
  std::ifstream Stream;
  long LineNumber = 0;
};

// A point array of a surface, every component as double (as vtkDataArray::GetComponent).
struct PointArray
{
  std::string name;
  int components = 1;
  std::vector<double> values; // components per point
};

// A polygonal surface as vtkPolyData holds it: cells are vertices, lines, polygons and
// strips in that order (input cell ids count them so); only the polygons are kept.
struct SurfaceData
{
  std::vector<double> points;               // 3 per point
  std::vector<std::int64_t> polygonOffsets; // polygon i: polygonPoints[offsets[i], offsets[i+1])
  std::vector<std::int64_t> polygonPoints;
  std::int64_t vertexCells = 0;
  std::int64_t lineCells = 0;
  std::int64_t stripCells = 0;
  std::vector<PointArray> pointArrays;
  std::vector<double> holePoints;     // TetGen's hole list (3 per point): regions to remove
  std::vector<double> regionPoints;   // TetGen's region list (x, y, z, attribute per point)
  std::vector<double> regionMaxSizes; // its volume bounds as sizes (1 per point; 0: none)

  std::int64_t PointCount() const { return static_cast<std::int64_t>(points.size() / 3); }
  std::int64_t PolygonCount() const
  {
    return polygonOffsets.empty() ? 0 : static_cast<std::int64_t>(polygonOffsets.size() - 1);
  }
};

// Object File Format: "OFF", then "points faces edges", points, faces "n v0 .. v(n-1)".
// Throws FileError naming the line.
SurfaceData ReadOff(const std::string& path);
// ReadOff's two parsers, for tests. The line parser (istream extraction, line by line) reads
// every file and names the line of a defect. The fast one reads the text of a usual file
// (plain decimal numbers, the tokens ReadOff needs at the start of each line) with the same
// result, and declines (false) anything else, which the line parser then reads.
SurfaceData ReadOffByLines(const std::string& path);
bool ReadOffFast(const std::string& text, SurfaceData& surface);

// A .vtp as vtkXMLPolyDataReader reads it: false (nothing thrown) when the file uses
// something this reader does not handle (another compressor, big-endian, several pieces,
// a malformed part): VTK reads it then, and names any defect.
bool ReadVtp(const std::string& path, SurfaceData& surface);

// An .stl (binary or ASCII) as vtkSTLReader reads it with merging on (StlFile.cxx): false
// (nothing thrown) for what this reader declines; VTK reads it then.
bool ReadStl(const std::string& path, SurfaceData& surface);

// Writes the mesh as vtkXMLUnstructuredGridWriter does for vtkTetMesher's output (appended
// raw binary; zlib blocks when `compress`). Throws FileError.
void WriteVtu(const SurfaceMeshOutput& mesh, const std::string& path, bool compress);

} // namespace cli
} // namespace tetmesher
