// The failure counter and check of the integration test programs (plain executables, no
// GoogleTest: they link VTK or the CLI's readers and take files on the command line).
#pragma once

#include <iostream>
#include <string>

namespace tetmesher
{
namespace testing
{

inline int& failures()
{
  static int count = 0;
  return count;
}

// Counts and prints a failed check; the program's exit status comes from failures().
inline void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    ++failures();
    std::cout << "FAIL " << what << "\n";
  }
}

} // namespace testing
} // namespace tetmesher
