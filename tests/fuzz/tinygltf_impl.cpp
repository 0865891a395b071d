// tinygltf's implementation, compiled into the fuzz target with the same instrumentation as our
// code (the packaged shared library is not). Images are never decoded (gltf_loader.cpp installs
// its own image callback), so stb_image is left out; the writer is only linked, never called.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <tiny_gltf.h>
