// Test support: typed tests over every packet width this build runs (1, 4, 8, 16).
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "simd/simd.h"

namespace raylane {

/// Test names W1, W4, W8, W16.
struct WidthName {
    template <class T>
    static std::string GetName(int) {
        std::string name = std::to_string(T::value);  // not "W" + ...: GCC 12 bug 105329
        return name.insert(0, 1, 'W');
    }
};

/// ::testing::Types<Width<1>, Width<4>, ...> for TYPED_TEST_SUITE. Builds configured with
/// RAYLANE_TEST_WIDTHS=native (scripts/test_widths.sh) take the native width alone: W = 1 and the
/// narrower widths are the release build's.
#if defined(RAYLANE_TEST_NATIVE_WIDTH_ONLY)
using Widths = ::testing::Types<Width<native_width>>;
#else
using Widths = supported_widths<::testing::Types>;
#endif

}  // namespace raylane
