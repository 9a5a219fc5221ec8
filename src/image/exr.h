// image: OpenEXR files (scan lines, one part) of films in named layers, with a data window and
// string attributes: the writer of `raylane render -o FILE.exr` and of the parts `raylane
// assemble` joins, and their reader.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "image/film.h"

namespace raylane {

/// One layer: its channels are `name.C` for each suffix C of `channels`, or C alone when `name` is
/// empty (the colour layer: R, G, B). Channel k holds component k of the film's pixels; a
/// layer of one channel holds the film's x component (reading it fills all three).
struct ExrLayer {
    std::string name;                   ///< "" for colour, else e.g. "normal", "depth"
    std::vector<std::string> channels;  ///< 1 or 3 suffixes, e.g. {"R", "G", "B"} or {"Z"}
    Film film;                          ///< the data window's pixels, row 0 at its top
};

/// An image: the display window is the whole frame [0, width) x [0, height); the data window,
/// the pixels the file holds, is [x0, x1) x [y0, y1) in frame pixels (not empty).
struct ExrImage {
    int width = 0, height = 0;
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    std::vector<ExrLayer> layers;  ///< each of (x1 - x0) x (y1 - y0) pixels
    /// String attributes of the header (e.g. "raylane:scene"), sorted by name as read back.
    std::vector<std::pair<std::string, std::string>> attributes;
    /// Channels stored as 32-bit floats, else as 16-bit halves (values past 65504 become
    /// infinite). read_exr: true when every channel is stored as 32-bit float.
    bool full_float = false;
};

/// The image of a whole film: display and data window the film, no layers.
ExrImage make_exr_image(int width, int height);

/// The string attribute `name`, or "" when the image has none.
std::string exr_attribute(const ExrImage& image, const std::string& name);

/// Writes a scan-line EXR, ZIP-compressed. Written to a temporary file and renamed, so an
/// interrupted write never leaves a half image under `path`. Throws std::runtime_error (with the
/// path) when it cannot write, std::invalid_argument when the image is inconsistent.
void write_exr(const std::string& path, const ExrImage& image);

/// Reads a single-part scan-line EXR, every channel as float, grouped into layers by the text
/// before the channel name's last dot, and its string attributes. The display window's origin
/// becomes (0, 0). Throws InputError ("path: reason", one line) for a missing, unreadable,
/// truncated or corrupt file, one that is not an EXR, a tiled, multi-part or deep one, an attribute
/// that claims more bytes than the file holds, a layer of other than 1 or 3 channels, a data window
/// outside the display window, or a frame larger than film.h allows.
ExrImage read_exr(const std::string& path);

/// read_exr of a file's bytes; `name` stands for the file in messages.
ExrImage read_exr_from_memory(std::string_view bytes, const std::string& name);

}  // namespace raylane
