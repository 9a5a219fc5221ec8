// numerics.md §0.2: flush-to-zero and denormals-are-zero are on wherever test code computes,
// the oneTBB workers of the tests' own parallel loops included (tests/support/test_main.cpp sets
// them before oneTBB starts; workers inherit them), so that oracles and the code they check see
// denormals the same way the renderer does.
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>
#include <xmmintrin.h>

#include <atomic>

namespace {

constexpr unsigned ftz_daz = 0x8040u;

bool flushes() {
    volatile float tiny = 1e-20f;
    const float product = tiny * tiny;  // 1e-40, a denormal: zero under FTZ
    volatile float denormal = 1e-40f;   // compares as zero under DAZ
    return product == 0.0f && !(denormal > 0.0f) && (_mm_getcsr() & ftz_daz) == ftz_daz;
}

TEST(FpuFlags, FlushToZeroIsOnInTheMainThreadAndInEveryWorker) {
    EXPECT_TRUE(flushes()) << "main thread";
    std::atomic<int> without{0}, tasks{0};
    tbb::parallel_for(0, 4096, 1, [&](int) {
        ++tasks;
        if (!flushes()) ++without;
    });
    EXPECT_EQ(tasks.load(), 4096);
    EXPECT_EQ(without.load(), 0) << "tasks that ran without FTZ/DAZ";
}

}  // namespace
