// The main of every test program: flush-to-zero and denormals-are-zero on, as in every render
// thread (numerics.md §0.2), then GoogleTest. Set before oneTBB starts its workers, which
// inherit the flags from the thread that creates them (checked by
// FpuFlags.FlushToZeroIsOnInTheMainThreadAndInEveryWorker).
#include <gtest/gtest.h>

#include "render/tiles.h"

int main(int argc, char** argv) {
    raylane::enable_flush_to_zero();
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
