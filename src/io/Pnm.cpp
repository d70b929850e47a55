// Based on: CMSC 23700 project 2a, sec. 6.2 (16-bit PGM height
// field) and 6.3 (PPM color, one pixel per grid cell); Netpbm P5/P6 layout.
#include "io/Pnm.h"

#include "core/Error.h"
#include "io/Files.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <algorithm>

namespace overflight {

namespace {

// Header tokenizer over untrusted bytes: every read is bounds-checked.
class HeaderReader {
public:
    HeaderReader(const std::uint8_t* data, std::size_t size, const std::string& subject)
        : data_(data), size_(size), subject_(subject) {}

    void expect_magic(char kind, const char* format) {
        if (size_ < 2 || data_[0] != 'P' || data_[1] != std::uint8_t(kind))
            throw Error(subject_, std::string("not a binary ") + format + " (expected magic P" + kind + ")");
        pos_ = 2;
    }

    // A decimal header field, after whitespace and '#' comments.
    long field(const char* name) {
        skip_space_and_comments();
        if (pos_ >= size_ || data_[pos_] < '0' || data_[pos_] > '9')
            throw Error(subject_, std::string("malformed header: expected ") + name);
        long value = 0;
        while (pos_ < size_ && data_[pos_] >= '0' && data_[pos_] <= '9') {
            value = value * 10 + (data_[pos_++] - '0');
            if (value > 1000000000L) throw Error(subject_, std::string("malformed header: ") + name + " is absurd");
        }
        return value;
    }

    // Exactly one whitespace byte separates maxval from the raster.
    std::size_t raster_start() {
        if (pos_ >= size_ || !is_space(data_[pos_])) throw Error(subject_, "malformed header: no raster after maxval");
        return pos_ + 1;
    }

private:
    static bool is_space(std::uint8_t c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }
    void skip_space_and_comments() {
        while (pos_ < size_) {
            if (is_space(data_[pos_])) {
                ++pos_;
            } else if (data_[pos_] == '#') {
                while (pos_ < size_ && data_[pos_] != '\n' && data_[pos_] != '\r') ++pos_;
            } else {
                break;
            }
        }
    }

    const std::uint8_t* data_;
    std::size_t size_;
    const std::string& subject_;
    std::size_t pos_ = 0;
};

struct PnmHeader {
    int width = 0, height = 0, maxval = 0;
    std::size_t raster = 0;       // offset of the first sample byte
    int bytes_per_sample = 1;
};

PnmHeader parse_header(const std::uint8_t* data, std::size_t size, const std::string& subject, char kind,
                       const char* format, int channels) {
    HeaderReader reader(data, size, subject);
    reader.expect_magic(kind, format);
    const long width = reader.field("width");
    const long height = reader.field("height");
    const long maxval = reader.field("maxval");
    if (width < 1 || height < 1 || width > kPnmMaxSide || height > kPnmMaxSide)
        throw Error(subject, "size " + std::to_string(width) + "x" + std::to_string(height) + " is outside 1.." +
                                 std::to_string(kPnmMaxSide));
    if (maxval < 1 || maxval > 65535)
        throw Error(subject, "maxval " + std::to_string(maxval) + " is outside 1..65535");
    PnmHeader h;
    h.width = int(width);
    h.height = int(height);
    h.maxval = int(maxval);
    h.raster = reader.raster_start();
    h.bytes_per_sample = maxval > 255 ? 2 : 1;
    // Check before allocating, so a lying header cannot make us allocate gigabytes.
    const std::size_t needed = std::size_t(width) * std::size_t(height) * std::size_t(channels) * h.bytes_per_sample;
    if (size - h.raster < needed)
        throw Error(subject, "truncated: " + std::to_string(width) + "x" + std::to_string(height) + " needs " +
                                 std::to_string(needed) + " data bytes, file has " + std::to_string(size - h.raster));
    return h;
}

void write_bytes(const std::string& path, const std::string& header, const std::vector<std::uint8_t>& body) {
    write_atomically(path, [&](const std::string& temp) {
        FILE* f = std::fopen(temp.c_str(), "wb");
        if (!f) throw Error(path, std::string("cannot create: ") + std::strerror(errno));
        bool ok = std::fwrite(header.data(), 1, header.size(), f) == header.size();
        ok = ok && std::fwrite(body.data(), 1, body.size(), f) == body.size();
        ok = (std::fclose(f) == 0) && ok;
        if (!ok) throw Error(path, "write failed (disk full?)");
    });
}

} // namespace

GrayImage16 parse_pgm(const std::uint8_t* data, std::size_t size, const std::string& subject) {
    const PnmHeader h = parse_header(data, size, subject, '5', "PGM", 1);
    GrayImage16 out;
    out.maxval = h.maxval;
    out.image.resize(h.width, h.height);
    const std::uint8_t* p = data + h.raster;
    auto& px = out.image.pixels;
    if (h.bytes_per_sample == 2) {
        for (std::size_t i = 0; i < px.size(); ++i) px[i] = std::uint16_t((p[2 * i] << 8) | p[2 * i + 1]);
    } else {
        for (std::size_t i = 0; i < px.size(); ++i) px[i] = p[i];
    }
    return out;
}

ColorImage parse_ppm(const std::uint8_t* data, std::size_t size, const std::string& subject) {
    const PnmHeader h = parse_header(data, size, subject, '6', "PPM", 3);
    ColorImage out(h.width, h.height);
    const std::uint8_t* p = data + h.raster;
    const std::size_t n = out.pixels.size() * 3;
    auto to8 = [&](std::size_t k) -> std::uint8_t {
        unsigned v = h.bytes_per_sample == 2 ? unsigned((p[2 * k] << 8) | p[2 * k + 1]) : unsigned(p[k]);
        if (h.maxval == 255) return std::uint8_t(v);
        if (v > unsigned(h.maxval)) v = unsigned(h.maxval);
        return std::uint8_t((v * 255u + unsigned(h.maxval) / 2) / unsigned(h.maxval));
    };
    for (std::size_t k = 0, i = 0; k < n; k += 3, ++i) out.pixels[i] = Rgb8{to8(k), to8(k + 1), to8(k + 2)};
    return out;
}

GrayImage16 read_pgm(const std::string& path) {
    const auto bytes = read_file_bytes(path);
    return parse_pgm(bytes.data(), bytes.size(), path);
}

ColorImage read_ppm(const std::string& path) {
    const auto bytes = read_file_bytes(path);
    return parse_ppm(bytes.data(), bytes.size(), path);
}

void write_pgm(const std::string& path, const Image2D<std::uint16_t>& image, int maxval) {
    if (maxval < 1 || maxval > 65535) throw Error(path, "maxval " + std::to_string(maxval) + " is outside 1..65535");
    if (image.width < 1 || image.height < 1) throw Error(path, "cannot write an empty image");
    const bool wide = maxval > 255;
    std::vector<std::uint8_t> body(image.pixels.size() * (wide ? 2 : 1));
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const unsigned v = std::min<unsigned>(image.pixels[i], unsigned(maxval));
        if (wide) {
            body[2 * i] = std::uint8_t(v >> 8);
            body[2 * i + 1] = std::uint8_t(v & 0xff);
        } else {
            body[i] = std::uint8_t(v);
        }
    }
    write_bytes(path, "P5\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n" +
                          std::to_string(maxval) + "\n", body);
}

void write_ppm(const std::string& path, const ColorImage& image) {
    if (image.width < 1 || image.height < 1) throw Error(path, "cannot write an empty image");
    std::vector<std::uint8_t> body(image.pixels.size() * 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        body[3 * i] = image.pixels[i].r;
        body[3 * i + 1] = image.pixels[i].g;
        body[3 * i + 2] = image.pixels[i].b;
    }
    write_bytes(path, "P6\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n255\n", body);
}

} // namespace overflight
