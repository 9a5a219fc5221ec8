// Test support: typed tests over every packet width this build runs (1, 4, 8, 16; without 1 in
// builds configured with RAYLANE_TEST_WIDTHS=simd).
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <type_traits>

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
/// RAYLANE_TEST_WIDTHS=simd (scripts/test_widths.sh) leave out W = 1, the scalar width, which
/// does not depend on the instruction set and the release build tests.
#if defined(RAYLANE_TEST_SIMD_WIDTHS_ONLY)
using Widths =
    std::conditional_t<width_supported<16>, ::testing::Types<Width<4>, Width<8>, Width<16>>,
                       std::conditional_t<width_supported<8>, ::testing::Types<Width<4>, Width<8>>,
                                          ::testing::Types<Width<4>>>>;
#else
using Widths = supported_widths<::testing::Types>;
#endif

}  // namespace raylane
