// The main of every test program: flush-to-zero and denormals-are-zero on, as in every render
// thread (numerics.md §0.2), then GoogleTest. Set before oneTBB starts its workers, which
// inherit the flags from the thread that creates them (checked by
// FpuFlags.FlushToZeroIsOnInTheMainThreadAndInEveryWorker). The models and textures are looked
// up in the shared folder beside the checkout, unless the caller set RAYLANE_MODEL_PATH.
#include <gtest/gtest.h>

#include <cstdlib>

#include "render/tiles.h"

int main(int argc, char** argv) {
    ::setenv("RAYLANE_MODEL_PATH", RAYLANE_SHARED_DIR "/models:" RAYLANE_SHARED_DIR "/textures", 0);
    raylane::enable_flush_to_zero();
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
