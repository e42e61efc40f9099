// tinygltf's implementation in the browser's build. On the desktop it is Debian's
// libtinygltf.so; in the page it is compiled from the same package's header, here once.
// (stb_image's and stb_image_write's implementations are image_codecs_web.cpp's.)
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
