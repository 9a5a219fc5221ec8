// image: the OpenEXR writer and reader (exr.h), over the OpenEXR library's scan-line files.
#include "image/exr.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfPartType.h>
#include <ImfStringAttribute.h>
#include <half.h>

#include <algorithm>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <stdexcept>
#include <string_view>
#include <system_error>

#include "core/error.h"
#include "image/write_file.h"
#include "scene/scene.h"

namespace raylane {

ExrImage make_exr_image(int width, int height) {
    ExrImage image;
    image.width = image.x1 = width;
    image.height = image.y1 = height;
    return image;
}

std::string exr_attribute(const ExrImage& image, const std::string& name) {
    for (const auto& [key, value] : image.attributes)
        if (key == name) return value;
    return {};
}

namespace {

std::string channel_name(const ExrLayer& layer, const std::string& suffix) {
    if (layer.name.empty()) return suffix;
    std::string name = layer.name;
    name += '.';
    name += suffix;
    return name;
}

/// A slice over component `c` of a film that covers `window` (row-major, vec3 pixels).
Imf::Slice film_slice(Film& film, int c, const Imath::Box2i& window) {
    float* first = &film.pixels[0][c];
    return Imf::Slice::Make(Imf::FLOAT, first, window, sizeof(vec3), sizeof(vec3) * film.width);
}

void check_image(const ExrImage& image) {
    const bool window_ok = image.width > 0 && image.height > 0 && 0 <= image.x0 &&
                           image.x0 < image.x1 && image.x1 <= image.width && 0 <= image.y0 &&
                           image.y0 < image.y1 && image.y1 <= image.height;
    if (!window_ok) throw std::invalid_argument("write_exr: the data window is outside the frame");
    for (const ExrLayer& layer : image.layers) {
        if (layer.channels.size() != 1 && layer.channels.size() != 3)
            throw std::invalid_argument("write_exr: a layer has 1 or 3 channels");
        if (layer.film.width != image.x1 - image.x0 || layer.film.height != image.y1 - image.y0)
            throw std::invalid_argument("write_exr: a layer's film is not the data window's size");
    }
}

}  // namespace

void write_exr(const std::string& path, const ExrImage& image) {
    check_image(image);
    const Imath::Box2i display(Imath::V2i(0, 0), Imath::V2i(image.width - 1, image.height - 1));
    const Imath::Box2i data(Imath::V2i(image.x0, image.y0), Imath::V2i(image.x1 - 1, image.y1 - 1));
    Imf::Header header(display, data);
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const auto& [name, value] : image.attributes)
        header.insert(name, Imf::StringAttribute(value));
    const Imf::PixelType type = image.full_float ? Imf::FLOAT : Imf::HALF;
    // OpenEXR writes a channel from a slice of its own type: the films' floats as they are, or
    // rounded to halves here. Slices take pointers to non-const, the writer only reads them.
    std::vector<Film> floats;
    std::vector<std::vector<half>> halves;
    floats.reserve(image.layers.size());
    halves.reserve(image.layers.size() * 3);
    Imf::FrameBuffer frame;
    for (const ExrLayer& layer : image.layers) {
        if (image.full_float) floats.push_back(layer.film);
        for (size_t c = 0; c < layer.channels.size(); ++c) {
            const std::string name = channel_name(layer, layer.channels[c]);
            header.channels().insert(name, Imf::Channel(type));
            if (image.full_float) {
                frame.insert(name, film_slice(floats.back(), int(c), data));
                continue;
            }
            std::vector<half>& channel = halves.emplace_back(layer.film.pixels.size());
            for (size_t i = 0; i < channel.size(); ++i)
                channel[i] = half(layer.film.pixels[i][glm::length_t(c)]);
            frame.insert(name, Imf::Slice::Make(Imf::HALF, channel.data(), data, sizeof(half),
                                                sizeof(half) * size_t(layer.film.width)));
        }
    }
    const std::string tmp = image_detail::temp_name(path);
    try {
        Imf::OutputFile file(tmp.c_str(), header);
        file.setFrameBuffer(frame);
        file.writePixels(image.y1 - image.y0);
    } catch (const std::exception& e) {
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        throw std::runtime_error(path + ": cannot write: " + e.what());
    }
    image_detail::commit_file(tmp, path);
}

namespace {

/// The place of a channel suffix in its layer: R, G, B and X, Y, Z in that order, others after.
int channel_rank(const std::string& suffix) {
    static const char* const order[] = {"R", "G", "B", "X", "Y", "Z"};
    for (int i = 0; i < 6; ++i)
        if (suffix == order[i]) return i % 3;
    return 3;
}

/// OpenEXR's message, on one line, without the file name it often starts with.
std::string exr_reason(const char* what, const std::string& path) {
    std::string s = what;
    s = s.substr(0, s.find('\n'));
    const std::string prefix = "Cannot read image file \"" + path + "\". ";
    if (s.rfind(prefix, 0) == 0) s.erase(0, prefix.size());
    return s;
}

/// The little-endian int32 at `at`.
int32_t int32_at(std::string_view bytes, size_t at) {
    uint32_t v = 0;
    for (int k = 3; k >= 0; --k) v = v << 8 | static_cast<unsigned char>(bytes[at + size_t(k)]);
    return static_cast<int32_t>(v);
}

/// Whether an attribute value of a type OpenEXR reads by its own content rather than by its
/// declared size keeps to that size: a channel list (entries of a name and 16 bytes, then an
/// empty name), a string vector (int32 lengths, each followed by that many bytes), a preview
/// image (width, height, then 4 bytes a pixel).
bool value_fits(std::string_view type, std::string_view value) {
    if (type == "chlist") {
        size_t at = 0;
        for (;;) {
            const size_t end = value.find('\0', at);
            if (end == std::string_view::npos || end - at > 255) return false;
            if (end == at) return end + 1 == value.size();
            at = end + 1 + 16;
            if (at > value.size()) return false;
        }
    }
    if (type == "stringvector") {
        for (size_t at = 0; at < value.size();) {
            if (value.size() - at < 4) return false;
            const int32_t n = int32_at(value, at);
            if (n < 0 || size_t(n) > value.size() - at - 4) return false;
            at += 4 + size_t(n);
        }
        return true;
    }
    if (type == "preview") {
        if (value.size() < 8) return false;
        const uint64_t w = uint32_t(int32_at(value, 0)), h = uint32_t(int32_at(value, 4));
        const uint64_t pixels = (value.size() - 8) / 4;  // w * h compared without overflow
        return (value.size() - 8) % 4 == 0 &&
               (w == 0 ? pixels == 0 : h == pixels / w && pixels % w == 0);
    }
    return true;
}

/// Why OpenEXR should not be given these bytes, or "": they must be a single-part scan-line file
/// whose header attributes fit in the file, with display and data windows of at most
/// max_film_side a side. OpenEXR allocates what a header declares before it reads it (an
/// attribute's size, a line offset table), so this walk of the header comes first.
std::string header_problem(std::string_view bytes) {
    if (bytes.size() < 8 || bytes.substr(0, 4) != std::string_view("\x76\x2f\x31\x01", 4))
        return "not an OpenEXR file (no EXR magic number)";
    const int32_t version = int32_at(bytes, 4);
    if (version & 0x200) return "a tiled EXR (Raylane reads scan-line files)";
    if (version & 0x800) return "holds deep data (Raylane reads flat images)";
    if (version & 0x1000) return "a multi-part EXR (Raylane reads single-part files)";
    const size_t longest_name = version & 0x400 ? 255 : 31;  // the long-names flag
    size_t at = 8;
    const auto text = [&](std::string& out) {
        const size_t end = bytes.find('\0', at);
        if (end == std::string_view::npos || end - at > longest_name) return false;
        out = bytes.substr(at, end - at);
        at = end + 1;
        return true;
    };
    const std::string damaged = "the header is cut short or damaged";
    for (std::string name, type;;) {
        if (!text(name)) return damaged;
        if (name.empty()) return {};
        if (!text(type) || bytes.size() - at < 4) return damaged;
        const int32_t size = int32_at(bytes, at);
        at += 4;
        if (size < 0 || size_t(size) > bytes.size() - at)
            return "header attribute \"" + name + "\" holds " + std::to_string(size) +
                   " bytes, past the end of the file (truncated or damaged)";
        const std::string_view value = bytes.substr(at, size_t(size));
        if (!value_fits(type, value)) return "header attribute \"" + name + "\" is damaged";
        if (type == "box2i" && size == 16) {
            const int64_t w = int64_t(int32_at(value, 8)) - int32_at(value, 0) + 1;
            const int64_t h = int64_t(int32_at(value, 12)) - int32_at(value, 4) + 1;
            if (w > max_film_side || h > max_film_side)
                return name + " of " + std::to_string(w) + "x" + std::to_string(h) +
                       " pixels (at most " + std::to_string(max_film_side) + " a side)";
        }
        at += size_t(size);
    }
}

/// An EXR held in memory, for OpenEXR's reader: a read past the end throws.
class MemoryStream : public Imf::IStream {
  public:
    MemoryStream(std::string_view bytes, const std::string& name)
        : Imf::IStream(name.c_str()), bytes_(bytes) {}
    bool read(char c[], int n) override {
        if (n < 0 || uint64_t(n) > bytes_.size() - at_)
            throw std::runtime_error("the file ends early (truncated)");
        std::copy_n(bytes_.data() + at_, n, c);
        at_ += uint64_t(n);
        return at_ < bytes_.size();
    }
    uint64_t tellg() override { return at_; }
    void seekg(uint64_t pos) override { at_ = std::min<uint64_t>(pos, bytes_.size()); }

  private:
    std::string_view bytes_;
    uint64_t at_ = 0;
};

ExrImage read_exr_file(const std::string& path, Imf::InputFile& file) {
    const Imf::Header& header = file.header();
    if (header.hasType() && header.type() != Imf::SCANLINEIMAGE)
        throw InputError(path + ": not a scan-line image (Raylane reads flat scan-line files)");
    const Imath::Box2i display = header.displayWindow();
    const Imath::Box2i data = header.dataWindow();
    ExrImage image;
    // 64-bit arithmetic: the corners are any ints in a corrupt file
    const int64_t width = int64_t(display.max.x) - display.min.x + 1;
    const int64_t height = int64_t(display.max.y) - display.min.y + 1;
    if (width < 1 || height < 1 || width > max_film_side || height > max_film_side ||
        width * height > max_film_pixels)
        throw InputError(path + ": a frame of " + std::to_string(width) + "x" +
                         std::to_string(height) + " pixels (at most " +
                         std::to_string(max_film_side) + " a side and 2^28 pixels)");
    if (data.min.x < display.min.x || data.min.y < display.min.y || data.max.x > display.max.x ||
        data.max.y > display.max.y || data.min.x > data.max.x || data.min.y > data.max.y)
        throw InputError(path + ": the data window is empty or reaches outside the display window");
    image.width = int(width);
    image.height = int(height);
    image.x0 = data.min.x - display.min.x;
    image.y0 = data.min.y - display.min.y;
    image.x1 = data.max.x - display.min.x + 1;
    image.y1 = data.max.y - display.min.y + 1;

    // channels into layers, by the text before the last dot
    std::map<std::string, std::vector<std::string>> layers;
    image.full_float = true;
    for (auto c = header.channels().begin(); c != header.channels().end(); ++c) {
        const std::string name = c.name();
        const size_t dot = name.rfind('.');
        const std::string layer = dot == std::string::npos ? "" : name.substr(0, dot);
        layers[layer].push_back(dot == std::string::npos ? name : name.substr(dot + 1));
        if (c.channel().xSampling != 1 || c.channel().ySampling != 1)
            throw InputError(path + ": channel " + name +
                             " is subsampled (Raylane reads one sample per pixel)");
        image.full_float = image.full_float && c.channel().type == Imf::FLOAT;
    }
    if (layers.empty()) throw InputError(path + ": has no channels");
    Imf::FrameBuffer frame;
    for (auto& [name, suffixes] : layers) {
        if (suffixes.size() != 1 && suffixes.size() != 3)
            throw InputError(path + ": layer \"" + name + "\" has " +
                             std::to_string(suffixes.size()) +
                             " channels (Raylane reads layers of 1 or 3)");
        std::stable_sort(suffixes.begin(), suffixes.end(),
                         [](const std::string& a, const std::string& b) {
                             return channel_rank(a) < channel_rank(b);
                         });
        ExrLayer layer;
        layer.name = name;
        layer.channels = suffixes;
        layer.film = make_film(image.x1 - image.x0, image.y1 - image.y0);
        image.layers.push_back(std::move(layer));
    }
    for (ExrLayer& layer : image.layers) {
        for (size_t c = 0; c < layer.channels.size(); ++c) {
            frame.insert(channel_name(layer, layer.channels[c]),
                         film_slice(layer.film, int(c), data));
        }
    }
    file.setFrameBuffer(frame);
    file.readPixels(data.min.y, data.max.y);
    for (ExrLayer& layer : image.layers)
        if (layer.channels.size() == 1)
            for (vec3& p : layer.film.pixels) p = vec3(p.x);

    for (auto a = header.begin(); a != header.end(); ++a)
        if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&a.attribute()))
            image.attributes.emplace_back(a.name(), s->value());
    return image;
}

/// read(), with every exception but InputError turned into one: "name: not a readable EXR: ...".
template <class Read>
ExrImage read_or_explain(const std::string& name, Read&& read) {
    try {
        return read();
    } catch (const InputError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw InputError(name + ": not a readable EXR (out of memory reading it)");
    } catch (const std::exception& e) {
        throw InputError(name + ": not a readable EXR: " + exr_reason(e.what(), name));
    }
}

}  // namespace

ExrImage read_exr(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(path + ": no such file");
    if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a directory");
    std::ifstream in(path, std::ios::binary);
    std::string bytes;
    try {
        bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    } catch (const std::bad_alloc&) {
        throw InputError(path + ": too large to read");
    }
    if (!in && !in.eof()) throw InputError(path + ": cannot be read");
    return read_exr_from_memory(bytes, path);
}

ExrImage read_exr_from_memory(std::string_view bytes, const std::string& name) {
    if (const std::string why = header_problem(bytes); !why.empty())
        throw InputError(name + ": not a readable EXR: " + why);
    return read_or_explain(name, [&] {
        MemoryStream stream(bytes, name);
        Imf::InputFile file(stream);
        return read_exr_file(name, file);
    });
}

}  // namespace raylane
