// render: tiles, flush-to-zero and progress.
#include "render/tiles.h"

#include <unistd.h>
#include <xmmintrin.h>

#include <algorithm>
#include <cstdio>

namespace raylane {

std::vector<Tile> make_tiles(int width, int height, int tile_size) {
    std::vector<Tile> tiles;
    tile_size = std::max(1, tile_size);
    tiles.reserve(size_t((width + tile_size - 1) / tile_size) *
                  size_t((height + tile_size - 1) / tile_size));
    for (int y = 0; y < height; y += tile_size)
        for (int x = 0; x < width; x += tile_size)
            tiles.push_back(
                {x, y, std::min(width, x + tile_size), std::min(height, y + tile_size)});
    return tiles;
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
