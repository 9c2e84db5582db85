// libFuzzer target: diagnosis and mesher on surfaces decoded from the fuzzer's bytes
// (FuzzSurfaceInput.h gives the format, FuzzSurfaceCheck.h the properties). Built by
// scripts/fuzz.sh with clang -fsanitize=fuzzer,address,undefined.
#include "FuzzSurfaceCheck.h"

#include <cstdio>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string problem = tetmesher::fuzz::runFuzzSurface(data, size);
  if (!problem.empty())
  {
    std::fprintf(stderr, "FuzzSurface: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
