// The one translation unit that compiles tinygltf (Debian's libtinygltf-dev header, the
// library's code behind TINYGLTF_IMPLEMENTATION) into gib_scene: compiled here rather than
// linked from Debian's libtinygltf.so so sanitizer builds instrument the parser the fuzz test
// drives. It uses nlohmann-json (nlohmann-json3-dev) and stb_image / stb_image_write
// (libstb-dev: headers under /usr/include/stb, code in libstb). Warnings are off for this file
// (CMakeLists.txt): it is third-party code.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
