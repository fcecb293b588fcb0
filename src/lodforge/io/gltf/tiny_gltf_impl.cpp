// The tinygltf implementation, compiled once. Images are not decoded
// (TINYGLTF_NO_STB_IMAGE*, set for the whole module in CMakeLists.txt):
// read_gltf keeps their bytes as they are, and external images are not read
// at all (TINYGLTF_NO_EXTERNAL_IMAGE), only their URIs are kept.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
