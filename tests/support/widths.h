// Test support: typed tests over the packet widths of the instruction set a test program is
// compiled for: the widths that set's code runs (sse4.2: 4, avx2: 8, avx512: 16 and the 8-wide
// leaf and node tests), and W = 1, the scalar width, in the sse4.2 program only (it does not
// depend on the set).
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

/// The widths as List<Width<W>...>: ::testing::Types for TYPED_TEST_SUITE, or WidthList.
template <template <class...> class List>
using tested_widths = std::conditional_t<
    native_width == 16, List<Width<8>, Width<16>>,
    std::conditional_t<native_width == 8, List<Width<8>>, List<Width<1>, Width<native_width>>>>;

/// ::testing::Types<Width<...>...> for TYPED_TEST_SUITE.
using Widths = tested_widths<::testing::Types>;

}  // namespace raylane
