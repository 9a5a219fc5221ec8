// scene: a camera's image size from the width and height a user asks for.
#include "scene/resolution.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "core/error.h"

namespace raylane {

void apply_resolution(Camera& cam, int width, int height) {
    if (width > 0 && height > 0) {
        cam.width = width;
        cam.height = height;
    } else if (width > 0) {
        cam.height = std::max(1, int(std::lround(double(width) * cam.height / cam.width)));
        cam.width = width;
    } else if (height > 0) {
        cam.width = std::max(1, int(std::lround(double(height) * cam.width / cam.height)));
        cam.height = height;
    }
    // one side given keeps the scene's aspect ratio, which may take the other past the limits
    if (cam.width > max_film_side || cam.height > max_film_side ||
        int64_t(cam.width) * cam.height > max_film_pixels)
        throw InputError("width and height: an image of " + std::to_string(cam.width) + "x" +
                         std::to_string(cam.height) + " pixels is too large (at most " +
                         std::to_string(max_film_side) + " a side and 2^28 pixels)");
}

}  // namespace raylane
