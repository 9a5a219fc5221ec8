// render: tiles, flush-to-zero and progress.
#include "render/tiles.h"

#include <unistd.h>
#include <xmmintrin.h>

#include <algorithm>
#include <cstdio>
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

void enable_flush_to_zero() { _mm_setcsr(_mm_getcsr() | 0x8040u); }  // FTZ | DAZ

void Progress::step() {
    if (!enabled || total == 0) return;  // no atomic per tile when nothing is shown
    const size_t n = done.fetch_add(1) + 1;
    const int percent = static_cast<int>(100 * n / total);
    int old = shown.load();
    if (percent > old && shown.compare_exchange_strong(old, percent)) {
        const double spent =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        // the pace of the first percent says little (a frame's first tiles are often sky)
        if (percent < 2) {
            std::fprintf(stderr, "\r\033[K%s: %3d%%, %.1f s", label, percent, spent);
        } else {
            const double left = spent / double(n) * double(total - n);
            std::fprintf(stderr, "\r\033[K%s: %3d%%, %.1f s, ~%.1f s left", label, percent, spent,
                         left);
        }
    }
}

void Progress::finish() {
    if (!enabled || shown.load() < 0) return;
    const double spent =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "\r\033[K%s: done in %.1f s\n", label, spent);
}

bool stderr_is_terminal() { return isatty(2) != 0; }

}  // namespace raylane
