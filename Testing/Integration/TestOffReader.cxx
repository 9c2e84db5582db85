// ReadOff's fast parser against its line parser (Apps/SurfaceFiles.h): on every .off given
// and on crafted variants (comments, CRLF, colours after the coordinates, counts on the
// keyword's line or the next, signs, exponents, odd tokens), the fast one either declines or
// gives the same points bit for bit and the same polygons; it must accept the usual files.
//   TestOffReader WORK_DIR FILE.off...
#include "IntegrationCheck.h"
#include "SurfaceFiles.h"

#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using tetmesher::testing::Check;
using tetmesher::testing::failures;

// 'accepted': whether the fast parser took the file (it must agree with the line parser).
void Compare(const std::string& path, const std::string& name, bool mustAccept)
{
  std::string text;
  Check(tetmesher::cli::ReadWholeFile(path, text), name + ": read");
  tetmesher::cli::SurfaceData fast;
  const bool accepted = tetmesher::cli::ReadOffFast(text, fast);
  if (mustAccept)
    Check(accepted, name + ": declined by the fast parser");
  if (!accepted)
    return;
  tetmesher::cli::SurfaceData lines;
  try
  {
    lines = tetmesher::cli::ReadOffByLines(path);
  }
  catch (const std::exception& e)
  {
    Check(false, name + ": the fast parser read what the line parser refuses: " + e.what());
    return;
  }
  Check(fast.points.size() == lines.points.size() &&
      std::memcmp(fast.points.data(), lines.points.data(), 8 * fast.points.size()) == 0,
    name + ": points differ");
  Check(fast.polygonOffsets == lines.polygonOffsets && fast.polygonPoints == lines.polygonPoints,
    name + ": polygons differ");
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::cerr << "usage: TestOffReader WORK_DIR FILE.off...\n";
    return 2;
  }
  const std::string work = argv[1];
  for (int i = 2; i < argc; ++i)
    Compare(argv[i], argv[i], true);
  const std::string tetra = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  const std::string faces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  struct Case
  {
    const char* name;
    std::string text;
    bool mustAccept;
  };
  const std::vector<Case> cases = {
    { "plain", "OFF\n4 4 6\n" + tetra + faces, true },
    { "counts on the keyword's line", "OFF 4 4 6\n" + tetra + faces, true },
    { "comments and blank lines",
      "# head\nOFF # k\n\n4 4 0 # counts\n" + tetra + "\n# x\n" + faces,
      true },
    { "CRLF",
      "OFF\r\n4 4 6\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n0 0 1\r\n3 0 2 1\r\n3 0 1 3\r\n3 0 3 2\r\n3 1 2 "
      "3\r\n",
      true },
    { "tabs, colours, signs and exponents",
      "COFF\n4\t4 0\n+0.0 -0 .0 255 0 0\n1e0 0. 0E+0\n-0.5e-1 1.000000000000000000000001 0\n0 0 "
      "123456789012345678901234567890e-29 1 1 1 1\n3 0 2 1 200 200 200\n3 +0 1 3\n3 0 3 2\n3 1 2 "
      "3\n",
      true },
    { "subnormal", "OFF\n4 4 0\n4.9e-324 0 0\n1 0 0\n0 1 0\n0 0 1\n" + faces, false },
    { "underflow to zero", "OFF\n4 4 0\n1e-400 0 0\n1 0 0\n0 1 0\n0 0 1\n" + faces, false },
    { "overflow", "OFF\n4 4 0\n1e400 0 0\n1 0 0\n0 1 0\n0 0 1\n" + faces, false },
    { "hex float", "OFF\n4 4 0\n0x1p-2 0 0\n1 0 0\n0 1 0\n0 0 1\n" + faces, false },
    { "nan", "OFF\n4 4 0\nnan 0 0\n1 0 0\n0 1 0\n0 0 1\n" + faces, false },
    { "junk after a number", "OFF\n4 4 0\n1.5abc 0 0\n1 0 0\n0 1 0\n0 0 1\n" + faces, false },
    { "vertical tab", "OFF\n4 4 0\n0\v0 0\n1 0 0\n0 1 0\n0 0 1\n" + faces, false },
    { "float count", "OFF\n4.0 4 0\n" + tetra + faces, false },
    { "id out of range", "OFF\n4 4 0\n" + tetra + "3 0 2 4\n3 0 1 3\n3 0 3 2\n3 1 2 3\n", false },
    { "too few lines", "OFF\n4 4 0\n" + tetra + "3 0 2 1\n", false },
    { "no keyword", "4 4 0\n" + tetra + faces, false },
    { "quad", "OFF\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n4 0 1 2 3\n3 0 1 4\n", true },
  };
  for (const Case& c : cases)
  {
    const std::string path = work + "/case.off";
    std::ofstream(path, std::ios::binary) << c.text;
    Compare(path, c.name, c.mustAccept);
  }
  std::cout << (failures() ? "FAILED" : "passed") << " (" << failures() << " failures)\n";
  return failures() ? 1 : 0;
}
