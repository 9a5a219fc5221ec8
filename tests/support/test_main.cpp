// The main of every test program: flush-to-zero and denormals-are-zero on, as in every render
// thread (numerics.md §0.2), in the main thread and in every oneTBB worker the tests use (their
// own parallel_for loops included), then GoogleTest.
#include <gtest/gtest.h>
#include <tbb/task_scheduler_observer.h>

#include "render/tiles.h"

namespace {

class FlushToZeroInWorkers : public tbb::task_scheduler_observer {
  public:
    FlushToZeroInWorkers() { observe(true); }
    void on_scheduler_entry(bool) override { raylane::enable_flush_to_zero(); }
};

}  // namespace

int main(int argc, char** argv) {
    raylane::enable_flush_to_zero();
    FlushToZeroInWorkers workers;
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
