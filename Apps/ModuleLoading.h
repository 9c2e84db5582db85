// Loading tetmesher's modules (libtetmesherVtk.so, libtetmesherSurfaceReaders.so) with dlopen.
#pragma once

namespace tetmesher
{
namespace cli
{

// dlopen of one of tetmesher's modules (RTLD_NOW | RTLD_LOCAL), by its path in the library
// directory next to the executable (bin/../lib), else by name through the RUNPATH. The path
// comes first because a bare name is looked up in the RUNPATH of the object that calls
// dlopen, which under ASan is its interceptor in libasan, not tetmesher. Null on failure
// (dlerror() says why).
void* LoadModule(const char* fileName);

} // namespace cli
} // namespace tetmesher
