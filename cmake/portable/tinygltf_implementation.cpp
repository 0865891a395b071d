// The portable build's tinygltf (cmake/Portable.cmake): the implementation half of Debian's
// tiny_gltf.h, which Debian otherwise compiles into a shared library only. stb_image's
// implementation comes from libstb.a, as it does for Debian's own libtinygltf.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
