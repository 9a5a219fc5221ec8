// image: PFM writing and reading (pfm.h).
#include "image/pfm.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "image/write_file.h"

namespace raylane {

void write_pfm(const std::string& path, const Film& film) {
    image_detail::write_file(path, [&](std::FILE* f) {
        bool ok = std::fprintf(f, "PF\n%d %d\n-1.0\n", film.width, film.height) > 0;
        const auto w = static_cast<size_t>(film.width);
        for (int y = film.height - 1; y >= 0 && ok && w > 0; --y)
            ok = std::fwrite(&film.at(0, y), sizeof(vec3), w, f) == w;
        return ok;
    });
}

std::optional<Film> read_pfm(const std::string& path, int width, int height) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    const size_t data = static_cast<size_t>(width) * static_cast<size_t>(height) * sizeof(vec3);
    if (ec || size < data || size > data + 64) return std::nullopt;
    std::ifstream f(path, std::ios::binary);
    std::string magic;
    int w = 0, h = 0;
    double scale = 0.0;
    if (!(f >> magic >> w >> h >> scale) || magic != "PF" || w != width || h != height ||
        !(scale < 0.0))
        return std::nullopt;
    if (f.get() != '\n') return std::nullopt;
    Film film = make_film(width, height);
    for (int y = height - 1; y >= 0; --y)
        if (!f.read(reinterpret_cast<char*>(&film.at(0, y)),
                    static_cast<std::streamsize>(sizeof(vec3)) * width))
            return std::nullopt;
    if (f.peek() != std::char_traits<char>::eof()) return std::nullopt;
    return film;
}

}  // namespace raylane
