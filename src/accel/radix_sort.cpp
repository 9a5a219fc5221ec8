// accel: the median-split build's radix sort (radix_sort.h): LSD passes over (key, id) items that
// skip the digits every key shares.
#include "accel/radix_sort.h"

#include <memory>
#include <utility>

#include "accel/order_key.h"

namespace raylane::RAYLANE_ISA_NS::median_detail {
namespace {

/// sort_ids_by_key in passes of `digit_bits` bits: an LSD radix sort of (key << 32 | id) items,
/// skipping the digits every key shares. Wide digits make fewer passes; narrow ones keep the
/// histograms small for small n. The first pass that moves anything makes the items from the
/// values as it scatters them (no array of items is written and read back first), and the last
/// writes the ids alone.
template <int digit_bits>
void sort_by_digits(const float* values, size_t n, uint32_t* out, uint64_t* items,
                    uint64_t* scratch) {
    constexpr int passes = (32 + digit_bits - 1) / digit_bits;
    constexpr uint32_t digit_mask = (1u << digit_bits) - 1u;
    auto histogram = std::make_unique<uint32_t[]>(size_t(passes) << digit_bits);
    for (size_t i = 0; i < n; ++i) {
        const uint32_t key = order_key(values[i]);
        for (int p = 0; p < passes; ++p)
            ++histogram[(size_t(p) << digit_bits) + ((key >> (digit_bits * p)) & digit_mask)];
    }
    // the passes that move anything: those where not every key has key0's digit
    const uint32_t key0 = order_key(values[0]);
    bool moves[passes] = {};
    int first = -1, last = -1;
    for (int p = 0; p < passes; ++p) {
        const uint32_t* count = histogram.get() + (size_t(p) << digit_bits);
        moves[p] = count[(key0 >> (digit_bits * p)) & digit_mask] != n;
        if (moves[p] && first < 0) first = p;
        if (moves[p]) last = p;
    }
    if (last < 0) {  // all keys equal: id order
        for (size_t i = 0; i < n; ++i) out[i] = static_cast<uint32_t>(i);
        return;
    }
    for (int p = first; p <= last; ++p) {
        if (!moves[p]) continue;
        uint32_t* offset = histogram.get() + (size_t(p) << digit_bits);
        uint32_t sum = 0;
        for (uint32_t d = 0; d <= digit_mask; ++d) {
            const uint32_t c = offset[d];
            offset[d] = sum;
            sum += c;
        }
        const uint32_t shift = digit_bits * static_cast<uint32_t>(p);
        if (p == first) {
            // from the values: keys recomputed (cheaper than an array of items written and read)
            for (size_t i = 0; i < n; ++i) {
                const uint32_t key = order_key(values[i]);
                const uint32_t d = (key >> shift) & digit_mask;
                if (p == last)
                    out[offset[d]++] = static_cast<uint32_t>(i);
                else
                    scratch[offset[d]++] = uint64_t(key) << 32 | i;
            }
        } else if (p == last) {
            for (size_t i = 0; i < n; ++i)
                out[offset[(items[i] >> (32 + shift)) & digit_mask]++] =
                    static_cast<uint32_t>(items[i]);
        } else {
            for (size_t i = 0; i < n; ++i)
                scratch[offset[(items[i] >> (32 + shift)) & digit_mask]++] = items[i];
        }
        std::swap(items, scratch);
    }
}

}  // namespace

void sort_ids_by_key(const float* values, size_t n, uint32_t* out, uint64_t* items,
                     uint64_t* scratch) {
    if (n >= wide_digits_from)
        sort_by_digits<16>(values, n, out, items, scratch);
    else
        sort_by_digits<8>(values, n, out, items, scratch);
}

}  // namespace raylane::RAYLANE_ISA_NS::median_detail
