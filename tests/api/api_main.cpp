// tests/api: the main of the public API's tests: the models and textures come from the shared
// folder beside the checkout unless the caller set RAYLANE_MODEL_PATH. Only the public headers
// are used here: the program links libraylane.so and compiles as C++17, as a user's would.
#include <gtest/gtest.h>

#include <cstdlib>

int main(int argc, char** argv) {
    ::setenv("RAYLANE_MODEL_PATH", RAYLANE_SHARED_DIR "/models:" RAYLANE_SHARED_DIR "/textures", 0);
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
