// render: image tiles run in parallel on oneTBB (progress on stderr: progress.h), each thread with
// flush-to-zero (core/float_modes.h), and cancelling a render. Both renderers use it.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cstdio>
#include <stdexcept>
#include <vector>

#include "core/float_modes.h"
#include "render/progress.h"
#include "render/render_params.h"

namespace raylane {

using Tile = PixelRect;

/// The tiles of a width x height frame's grid of tile_size squares (the last row and column
/// narrower) that meet `region`; every tile when the region is empty.
std::vector<Tile> make_tiles(int width, int height, int tile_size, const PixelRect& region = {});

/// Part `index` (0 to count - 1) of `count` rectangles that cut a width x height frame along the
/// lines of its tile grid (make_tiles): the tile rows in min(count, rows) bands of about equal
/// height, each band's columns in as many parts as fall to it. Row-major: part 0 at the top left.
/// Throws std::invalid_argument when some part would hold no tile.
PixelRect tile_part(int width, int height, int tile_size, int index, int count);

/// The region a render covers: params.region, or the whole frame when it is empty. Throws
/// std::invalid_argument when the region is not inside the frame.
PixelRect render_region(const RenderParams& params, int width, int height);

/// Thrown by for_each_tile when a cancel was requested: the render is incomplete.
struct Cancelled : std::runtime_error {
    Cancelled() : std::runtime_error("interrupted") {}
};

/// Asks every running and later for_each_tile to stop: tiles not yet started are skipped and
/// for_each_tile throws Cancelled. Async-signal-safe (a lock-free atomic store): the command
/// line calls it from its SIGINT / SIGTERM handler.
void request_cancel();
bool cancel_requested();

/// A render's counts, one copy per thread (`local()`), summed when the tiles are done: a tile adds
/// its counts without atomics (a locked add also waits for the tile's earlier stores).
using PerThreadStats = tbb::enumerable_thread_specific<RenderStats>;

/// Runs body(tile) for every tile on `threads` threads (0 = all). Each tile runs on one thread;
/// the result must not depend on which thread or in what order. Throws Cancelled if a cancel
/// was requested before it returned.
template <class Body>
void for_each_tile(const std::vector<Tile>& tiles, int threads, Progress& progress, Body&& body) {
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1),
                          [&](const tbb::blocked_range<size_t>& range) {
                              enable_flush_to_zero();
                              for (size_t i = range.begin(); i != range.end(); ++i) {
                                  if (cancel_requested()) return;
                                  body(tiles[i]);
                                  progress.step();
                              }
                          });
    });
    if (cancel_requested()) {
        if (progress.enabled) std::fputc('\n', stderr);
        throw Cancelled();
    }
    progress.finish();
}

}  // namespace raylane
