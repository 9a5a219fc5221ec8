// accel: the median-split build's radix sort: primitive ids ordered by one axis's centroids, one
// sort per axis at the start of every subtree build (radix_sort.cpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "simd/namespace.h"

namespace raylane::RAYLANE_ISA_NS::median_detail {

/// The key count from which the sort uses 16-bit digits (two passes with histograms of 65,536
/// counts) instead of 8-bit ones (four passes of 256 counts).
inline constexpr size_t wide_digits_from = size_t(1) << 16;

/// Sorts the ids 0 .. n-1 (n >= 1) by order_key(values[id]), stably (equal keys in id order),
/// into `out`. `items` and `scratch` hold n 8-byte items each; both are overwritten.
void sort_ids_by_key(const float* values, size_t n, uint32_t* out, uint64_t* items,
                     uint64_t* scratch);

}  // namespace raylane::RAYLANE_ISA_NS::median_detail
