// core: FNV-1a, 64 bits (Fowler, Noll, Vo; the published offset basis and prime): the hash that
// names a reference render in the report's cache and a scene in the parts of a frame.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace raylane {

struct Fnv1a {
    uint64_t h = 14695981039346656037ull;
    void bytes(const void* data, size_t n) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
    }
    /// The value's bytes (pass a fixed-width type: the hash depends on its size).
    template <class T>
    void number(T x) {
        bytes(&x, sizeof x);
    }
    /// A count first, so that [a][bc] and [ab][c] differ.
    void text(const std::string& s) {
        number(uint64_t(s.size()));
        bytes(s.data(), s.size());
    }
    template <class T>
    void array(const std::vector<T>& v) {
        number(uint64_t(v.size()));
        bytes(v.data(), v.size() * sizeof(T));
    }
};

}  // namespace raylane
