// io: stb_image's decoders (configured in io/stb_image.h) and the allocation hooks they call.
//
// This file alone is compiled with -fwrapv, and without UBSan's signed-integer-overflow check
// (CMakeLists.txt). stb_image 2.27, the Debian 12 version, lets a corrupt JPEG overflow `int`
// in its Huffman decoding: the DC predictor adds up unchecked differences and is multiplied by
// the quantiser (stbi__jpeg_decode_block; checked from stb_image 2.28 on). Found by fuzz_image.
// -fwrapv makes that arithmetic wrap, as the decoder assumes, so a corrupt file decodes to wrong
// pixels (or is rejected) with defined behaviour in every build; no other check is turned off.
// Our own code stays in io/load_image.cpp, under every sanitizer check. The stb_image.h included
// here is 2.27 with bit-count guards after stb 2.28's on the Huffman data
// (cmake/patch_stb_image.cmake).
#define STB_IMAGE_IMPLEMENTATION
#include "io/stb_image.h"

#include <cstdlib>

namespace raylane {

thread_local size_t stb_allocation_limit = size_t{1} << 20;

void* stb_malloc(size_t bytes) {
    return bytes > stb_allocation_limit ? nullptr : std::malloc(bytes);
}
void* stb_realloc(void* p, size_t bytes) {
    return bytes > stb_allocation_limit ? nullptr : std::realloc(p, bytes);
}
void stb_free(void* p) { std::free(p); }

}  // namespace raylane
