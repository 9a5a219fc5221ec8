// bench: ray files, (N, 6) float32 NumPy arrays (.npy: origin x y z, direction x y z per row),
// as numpy.save or raylane.save_rays writes them; and a hits file written back for checks.
#pragma once

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace raylane::bench {

/// The rays of a .npy file: 6 floats per ray. Throws std::runtime_error "path: reason" unless
/// the file is a little-endian float32 array of shape (N, 6) in C order.
inline std::vector<float> read_ray_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open");
    auto fail = [&](const std::string& why) {
        std::string m = path;
        m.append(": ").append(why).append(" (expected an (N, 6) float32 .npy file)");
        return std::runtime_error(m);
    };
    char magic[8];
    if (!in.read(magic, 8) || std::memcmp(magic, "\x93NUMPY", 6) != 0)
        throw fail("not a NumPy file");
    uint32_t header_len = 0;
    if (magic[6] == 1) {
        unsigned char b[2];
        if (!in.read(reinterpret_cast<char*>(b), 2)) throw fail("truncated header");
        header_len = uint32_t(b[0]) | uint32_t(b[1]) << 8;
    } else {
        unsigned char b[4];
        if (!in.read(reinterpret_cast<char*>(b), 4)) throw fail("truncated header");
        header_len =
            uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
    }
    if (header_len > (1u << 20)) throw fail("header too long");
    std::string header(header_len, '\0');
    if (!in.read(header.data(), header_len)) throw fail("truncated header");
    std::string compact;
    for (char c : header)
        if (c != ' ') compact += c;
    if (compact.find("'descr':'<f4'") == std::string::npos) throw fail("dtype is not float32");
    if (compact.find("'fortran_order':False") == std::string::npos)
        throw fail("array is in Fortran order");
    const size_t shape = compact.find("'shape':(");
    if (shape == std::string::npos) throw fail("no shape");
    std::istringstream dims(compact.substr(shape + 9));
    uint64_t rows = 0;
    char comma = 0;
    int cols = 0;
    if (!(dims >> rows >> comma >> cols) || comma != ',' || cols != 6 || dims.get() != ')')
        throw fail("shape is not (N, 6)");
    if (rows > (uint64_t(1) << 32)) throw fail("more than 2^32 rays");
    std::vector<float> rays(size_t(rows) * 6);
    if (!in.read(reinterpret_cast<char*>(rays.data()), std::streamsize(rays.size() * 4)))
        throw fail("file ends before its " + std::to_string(rows) + " rays");
    return rays;
}

/// Writes an (N, cols) float64 .npy file (version 1.0).
inline void write_npy(const std::string& path, const std::vector<double>& values, size_t cols) {
    std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (";
    header.append(std::to_string(values.size() / cols)).append(", ");
    header.append(std::to_string(cols)).append("), }");
    while ((10 + header.size() + 1) % 64 != 0) header += ' ';
    header += '\n';
    std::ofstream out(path, std::ios::binary);
    out.write("\x93NUMPY\x01\x00", 8);
    const char len[2] = {char(header.size() & 0xff), char(header.size() >> 8)};
    out.write(len, 2);
    out.write(header.data(), std::streamsize(header.size()));
    out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * 8));
    if (!out) throw std::runtime_error(path + ": cannot write");
}

}  // namespace raylane::bench
