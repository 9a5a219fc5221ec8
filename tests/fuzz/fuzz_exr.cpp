// fuzz: libFuzzer target for the EXR reader (image/exr.h, read_exr_from_memory, over the OpenEXR
// library). Seeds: tests/fuzz/corpus/exr/ (written by raylane render); run by scripts/fuzz.sh.
//
// OpenEXR itself is not instrumented, so the search is guided by the reader's own code only; the
// sanitizers still see every byte OpenEXR writes into the reader's films. Data windows past
// 128 pixels a side are refused by OpenEXR's own size check here: a header of a few hundred
// bytes may declare hundreds of layers of a frame of 2^28 pixels, which the reader would then
// allocate, by design.
#include <ImfHeader.h>

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "fuzz_check.h"
#include "image/exr.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    Imf::Header::setMaxImageSize(128, 128);
    Imf::Header::setMaxTileSize(128, 128);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        const raylane::ExrImage image = raylane::read_exr_from_memory(bytes, "fuzz.exr");
        using raylane::fuzz::require;
        require(0 <= image.x0 && image.x0 < image.x1 && image.x1 <= image.width,
                "data window x outside the frame");
        require(0 <= image.y0 && image.y0 < image.y1 && image.y1 <= image.height,
                "data window y outside the frame");
        require(!image.layers.empty(), "no layers");
        for (const raylane::ExrLayer& layer : image.layers) {
            require(layer.channels.size() == 1 || layer.channels.size() == 3, "channel count");
            require(layer.film.width == image.x1 - image.x0 &&
                        layer.film.height == image.y1 - image.y0 &&
                        layer.film.pixels.size() ==
                            size_t(layer.film.width) * size_t(layer.film.height),
                    "film size");
        }
    } catch (const raylane::InputError&) {
        // Expected for bad input; any other exception escapes and is a finding.
    }
    return 0;
}
