// The one translation unit that compiles tinygltf's implementation. Debian builds tinygltf
// against system nlohmann-json and stb; libstb already provides the stb_image and
// stb_image_write implementations, so no STB_*_IMPLEMENTATION defines here. Draco support in
// tinygltf stays off: engine/asset/draco_decode.cpp decodes KHR_draco_mesh_compression itself.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
