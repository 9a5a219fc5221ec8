// image: the zlib stream inside a PNG, compressed in parallel chunks (deflate.h).
#include "image/deflate.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstring>

namespace raylane {

namespace {

constexpr size_t chunk_bytes = size_t(256) << 10;
constexpr int hash_bits = 15;
constexpr size_t window = 32768;  ///< the farthest a match may reach back
constexpr size_t max_match = 258;
constexpr uint32_t adler_base = 65521;

/// A code of the bit stream: `n` bits, the first in the lowest bit.
struct Code {
    uint32_t bits = 0;
    int n = 0;
};

uint32_t reverse_bits(uint32_t code, int n) {
    uint32_t r = 0;
    for (int i = 0; i < n; ++i) r |= ((code >> i) & 1u) << (n - 1 - i);
    return r;
}

/// The fixed Huffman code of a literal/length symbol (RFC 1951, 3.2.6); Huffman codes go into
/// the stream from their most significant bit, hence reversed.
Code symbol_code(int symbol) {
    const auto s = static_cast<uint32_t>(symbol);
    if (symbol < 144) return {reverse_bits(0x30u + s, 8), 8};
    if (symbol < 256) return {reverse_bits(0x190u + s - 144u, 9), 9};
    if (symbol < 280) return {reverse_bits(s - 256u, 7), 7};
    return {reverse_bits(0xc0u + s - 280u, 8), 8};
}

constexpr std::array<uint16_t, 29> length_base = {3,  4,  5,  6,   7,   8,   9,   10,  11, 13,
                                                  15, 17, 19, 23,  27,  31,  35,  43,  51, 59,
                                                  67, 83, 99, 115, 131, 163, 195, 227, 258};
constexpr std::array<uint8_t, 29> length_extra = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                                  2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
constexpr std::array<uint16_t, 30> distance_base = {
    1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,   65,    97,    129,
    193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
constexpr std::array<uint8_t, 30> distance_extra = {0, 0, 0,  0,  1,  1,  2,  2,  3,  3,
                                                    4, 4, 5,  5,  6,  6,  7,  7,  8,  8,
                                                    9, 9, 10, 10, 11, 11, 12, 12, 13, 13};

/// Every code the compressor writes, made once: the literals, the length of a match (symbol
/// and extra bits in one code, at most 13 bits) and its distance symbol by distance (a table
/// for the first 256, then one per 128).
struct Codes {
    std::array<Code, 256> literal;
    std::array<Code, max_match + 1> length;
    Code end_of_block;
    std::array<uint8_t, 256> near_distance;  ///< distance symbol of distances 1 .. 256
    std::array<uint8_t, 256> far_distance;   ///< of distances 257 .. 32768, by (d - 1) >> 7

    Codes() {
        for (int b = 0; b < 256; ++b) literal[size_t(b)] = symbol_code(b);
        end_of_block = symbol_code(256);
        for (size_t len = 3; len <= max_match; ++len) {
            size_t s = 0;
            while (s + 1 < length_base.size() && length_base[s + 1] <= len) ++s;
            const Code c = symbol_code(257 + int(s));
            length[len] = {c.bits | uint32_t(len - length_base[s]) << c.n, c.n + length_extra[s]};
        }
        auto symbol_of = [](size_t d) {
            size_t s = 0;
            while (s + 1 < distance_base.size() && distance_base[s + 1] <= d) ++s;
            return static_cast<uint8_t>(s);
        };
        for (size_t d = 1; d <= 256; ++d) near_distance[d - 1] = symbol_of(d);
        for (size_t k = 2; k < 256; ++k) far_distance[k] = symbol_of((k << 7) + 1);
    }

    Code distance(size_t d) const {
        const uint8_t s = d <= 256 ? near_distance[d - 1] : far_distance[(d - 1) >> 7];
        return {reverse_bits(s, 5) | uint32_t(d - distance_base[s]) << 5, 5 + distance_extra[s]};
    }
};

const Codes& codes() {
    static const Codes c;
    return c;
}

/// Bits into bytes, the first bit in the lowest bit of a byte.
struct BitWriter {
    std::vector<uint8_t>& out;
    uint64_t bits = 0;
    int count = 0;

    void put(Code c) {  // c.n <= 32
        bits |= uint64_t(c.bits) << count;
        count += c.n;
        while (count >= 8) {
            out.push_back(static_cast<uint8_t>(bits));
            bits >>= 8;
            count -= 8;
        }
    }
    /// Zero bits up to the next byte.
    void align() {
        if (count > 0) out.push_back(static_cast<uint8_t>(bits));
        bits = 0;
        count = 0;
    }
};

uint32_t load32(const uint8_t* p) {
    uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
}

/// Multiplicative hash of four bytes to hash_bits bits.
uint32_t hash(uint32_t four) { return (four * 2654435761u) >> (32 - hash_bits); }

/// The length of the common prefix of a and b, at most `limit`.
size_t match_length(const uint8_t* a, const uint8_t* b, size_t limit) {
    size_t n = 0;
    while (n + 8 <= limit) {
        uint64_t x, y;
        std::memcpy(&x, a + n, 8);
        std::memcpy(&y, b + n, 8);
        if (x != y) return n + static_cast<size_t>(__builtin_ctzll(x ^ y) >> 3);
        n += 8;
    }
    while (n < limit && a[n] == b[n]) ++n;
    return n;
}

/// One chunk, appended to `out` as a fixed-Huffman block followed by an empty stored block (LEN
/// 0, NLEN 0xffff), or as stored blocks when they are no larger: either way the stream is on a
/// byte boundary after it.
void compress_chunk(const uint8_t* data, size_t n, std::vector<uint8_t>& out) {
    const Codes& c = codes();
    const size_t start = out.size();
    {
        std::vector<int32_t> head(size_t(1) << hash_bits, -1);  // last position of each hash
        BitWriter w{out};
        w.put({0b010, 3});  // BFINAL = 0, BTYPE = 01: fixed Huffman
        size_t i = 0;
        while (i + 4 <= n) {
            const uint32_t four = load32(data + i);
            const uint32_t h = hash(four);
            const int32_t candidate = head[h];
            head[h] = static_cast<int32_t>(i);
            if (candidate >= 0 && i - size_t(candidate) <= window &&
                load32(data + candidate) == four) {
                const size_t len = 4 + match_length(data + candidate + 4, data + i + 4,
                                                    std::min(max_match, n - i) - 4);
                w.put(c.length[len]);
                w.put(c.distance(i - size_t(candidate)));
                // the positions inside the match go into the table too: files 16 % smaller
                // (stb's size), 15 % slower
                for (size_t j = i + 1; j < i + len && j + 4 <= n; ++j)
                    head[hash(load32(data + j))] = static_cast<int32_t>(j);
                i += len;
            } else {
                w.put(c.literal[data[i]]);
                ++i;
            }
        }
        for (; i < n; ++i) w.put(c.literal[data[i]]);
        w.put(c.end_of_block);
        w.put({0b000, 3});  // BFINAL = 0, BTYPE = 00: an empty stored block, which aligns
        w.align();
        out.insert(out.end(), {uint8_t(0x00), uint8_t(0x00), uint8_t(0xff), uint8_t(0xff)});
    }
    // stored blocks of at most 65535 bytes when they are smaller (incompressible data); each
    // starts and ends on a byte
    const size_t stored = n + 5 * ((n + 65534) / 65535);
    if (out.size() - start >= stored) {
        out.resize(start);
        for (size_t j = 0; j < n; j += 65535) {
            const auto len = static_cast<uint16_t>(std::min<size_t>(65535, n - j));
            out.push_back(0);  // BFINAL = 0, BTYPE = 00, then the byte's remaining bits
            out.push_back(static_cast<uint8_t>(len));
            out.push_back(static_cast<uint8_t>(len >> 8));
            out.push_back(static_cast<uint8_t>(~len));
            out.push_back(static_cast<uint8_t>(~len >> 8));
            out.insert(out.end(), data + j, data + j + len);
        }
    }
}

/// (a, b) of RFC 1950 over `data`, from a = 1, b = 0.
void adler_sums(const uint8_t* data, size_t n, uint32_t& a, uint32_t& b) {
    a = 1;
    b = 0;
    while (n > 0) {
        const size_t run = std::min<size_t>(n, 5552);  // no overflow of b before the modulo
        for (size_t i = 0; i < run; ++i) {
            a += data[i];
            b += a;
        }
        a %= adler_base;
        b %= adler_base;
        data += run;
        n -= run;
    }
}

}  // namespace

uint32_t adler32(std::span<const uint8_t> data) {
    uint32_t a, b;
    adler_sums(data.data(), data.size(), a, b);
    return b << 16 | a;
}

std::vector<uint8_t> zlib_compress(std::span<const uint8_t> data) {
    const size_t n = data.size();
    const size_t chunks = std::max<size_t>(1, (n + chunk_bytes - 1) / chunk_bytes);
    std::vector<std::vector<uint8_t>> parts(chunks);
    std::vector<uint32_t> sum_a(chunks), sum_b(chunks);
    tbb::parallel_for(size_t(0), chunks, [&](size_t k) {
        const size_t first = k * chunk_bytes, count = std::min(chunk_bytes, n - first);
        if (n > 0) {
            parts[k].reserve(count / 4 + 64);
            compress_chunk(data.data() + first, count, parts[k]);
        }
        adler_sums(data.data() + first, n > 0 ? count : 0, sum_a[k], sum_b[k]);
    });
    // Adler-32 of the chunks in a row: after a chunk of m bytes with sums (a', b') from (1, 0),
    // a = a + a' - 1 and b = b + m a + b' - m
    uint64_t a = 1, b = 0;
    for (size_t k = 0; k < chunks; ++k) {
        const uint64_t m = k * chunk_bytes < n ? std::min(chunk_bytes, n - k * chunk_bytes) : 0;
        const uint64_t mm = m % adler_base;
        b = (b + mm * a + sum_b[k] + adler_base - mm) % adler_base;
        a = (a + sum_a[k] + adler_base - 1) % adler_base;
    }
    size_t total = 2 + 2 + 4;
    for (const auto& p : parts) total += p.size();
    std::vector<uint8_t> out;
    out.reserve(total);
    out.push_back(0x78);  // deflate, 32 KiB window
    out.push_back(0x01);  // no dictionary, "fastest"; (0x78 << 8 | 0x01) % 31 == 0
    for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
    out.push_back(0x03);  // the last block: BFINAL = 1, BTYPE = 01, end of block, zero padding
    out.push_back(0x00);
    const auto checksum = static_cast<uint32_t>(b << 16 | a);
    for (int shift = 24; shift >= 0; shift -= 8)
        out.push_back(static_cast<uint8_t>(checksum >> shift));
    return out;
}

}  // namespace raylane
