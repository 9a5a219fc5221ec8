// The main of every test program: flush-to-zero and denormals-are-zero on, as in every render
// thread (numerics.md §0.2), then GoogleTest. Set before oneTBB starts its workers, which
// inherit the flags from the thread that creates them (checked by
// FpuFlags.FlushToZeroIsOnInTheMainThreadAndInEveryWorker). The models and textures are looked
// up in the shared folder beside the checkout, unless the caller set RAYLANE_MODEL_PATH. A
// program compiled for one instruction set uses that set throughout, whatever RAYLANE_ISA says.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "core/float_modes.h"
#include "core/isa.h"

int main(int argc, char** argv) {
    ::setenv("RAYLANE_MODEL_PATH", RAYLANE_SHARED_DIR "/models:" RAYLANE_SHARED_DIR "/textures", 0);
#if defined(RAYLANE_ISA_ENUM)
    raylane::use_isa(raylane::Isa::RAYLANE_ISA_ENUM);
    std::printf("instruction set %s, W = %d\n", raylane::isa_name(raylane::active_isa()),
                raylane::isa_width(raylane::active_isa()));
#endif
    raylane::enable_flush_to_zero();
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
