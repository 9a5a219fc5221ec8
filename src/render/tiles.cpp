// render: tiles, their grid's parts, and cancelling a render (tiles.h).
#include "render/tiles.h"

#include <algorithm>
#include <atomic>
#include <string>

namespace raylane {

std::vector<Tile> make_tiles(int width, int height, int tile_size, const PixelRect& region) {
    std::vector<Tile> tiles;
    tile_size = std::max(1, tile_size);
    const PixelRect r = region.empty() ? PixelRect{0, 0, width, height} : region;
    // the grid's rows and columns that meet r
    const int tx0 = r.x0 / tile_size, ty0 = r.y0 / tile_size;
    const int tx1 = (r.x1 + tile_size - 1) / tile_size, ty1 = (r.y1 + tile_size - 1) / tile_size;
    tiles.reserve(size_t(std::max(0, tx1 - tx0)) * size_t(std::max(0, ty1 - ty0)));
    for (int ty = ty0; ty < ty1; ++ty) {
        for (int tx = tx0; tx < tx1; ++tx) {
            const int x = tx * tile_size, y = ty * tile_size;
            tiles.push_back(
                {x, y, std::min(width, x + tile_size), std::min(height, y + tile_size)});
        }
    }
    return tiles;
}

PixelRect tile_part(int width, int height, int tile_size, int index, int count) {
    tile_size = std::max(1, tile_size);
    const int rows = (height + tile_size - 1) / tile_size;
    const int cols = (width + tile_size - 1) / tile_size;
    if (count < 1 || index < 0 || index >= count)
        throw std::invalid_argument(std::to_string(index) + " is not a part of " +
                                    std::to_string(count));
    const int bands = std::min(count, rows);
    // band b holds parts [first(b), first(b + 1)): count / bands each, one more for the first
    // count % bands bands
    auto first = [&](int b) { return b * (count / bands) + std::min(b, count % bands); };
    if (first(1) - first(0) > cols) {  // the first band holds the most parts
        throw std::invalid_argument(
            std::to_string(count) + " parts of a frame of " + std::to_string(cols) + "x" +
            std::to_string(rows) + " tiles of " + std::to_string(tile_size) +
            " pixels: a part would hold no tile (at most " + std::to_string(cols * rows) + ")");
    }
    int band = 0;
    while (first(band + 1) <= index) ++band;
    const int parts = first(band + 1) - first(band);
    const int k = index - first(band);
    const int r0 = band * rows / bands, r1 = (band + 1) * rows / bands;
    const int c0 = k * cols / parts, c1 = (k + 1) * cols / parts;
    return {c0 * tile_size, r0 * tile_size, std::min(width, c1 * tile_size),
            std::min(height, r1 * tile_size)};
}

PixelRect render_region(const RenderParams& params, int width, int height) {
    const PixelRect& r = params.region;
    if (r.empty()) return {0, 0, width, height};
    if (r.x0 < 0 || r.y0 < 0 || r.x1 > width || r.y1 > height)
        throw std::invalid_argument("render region outside the frame");
    return r;
}

namespace {
std::atomic<bool> cancel_flag{false};
static_assert(std::atomic<bool>::is_always_lock_free);  // safe to store from a signal handler
}  // namespace

void request_cancel() { cancel_flag.store(true, std::memory_order_relaxed); }
bool cancel_requested() { return cancel_flag.load(std::memory_order_relaxed); }

}  // namespace raylane
