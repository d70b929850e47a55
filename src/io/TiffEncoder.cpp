// Based on: Adobe, "TIFF Revision 6.0"; OGC GeoTIFF 1.1; GDAL's GTiff
// driver (the tags it writes, harvested from a one-sample file).
#include "io/TiffEncoder.h"

#include "io/Gdal.h"

#include <cpl_conv.h>
#include <cpl_vsi.h>
#include <libdeflate.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <tuple>

namespace overflight {

namespace {

static_assert(std::endian::native == std::endian::little, "the encoder writes host-order samples into an II TIFF");

enum : std::uint16_t { kShort = 3, kLong = 4, kAscii = 2, kDouble = 12 };

struct Entry {
    std::uint16_t tag = 0, type = 0;
    std::uint32_t count = 0;
    std::vector<std::uint8_t> value; // count values of type, little-endian
};

std::size_t type_bytes(std::uint16_t type) {
    switch (type) {
    case 1: case 2: case 6: case 7: return 1;
    case 3: case 8: return 2;
    case 4: case 9: case 11: case 13: return 4;
    default: return 8;
    }
}

template <class T> Entry entry(std::uint16_t tag, std::uint16_t type, const std::vector<T>& values) {
    Entry e{tag, type, std::uint32_t(values.size()), {}};
    e.value.resize(values.size() * sizeof(T));
    std::memcpy(e.value.data(), values.data(), e.value.size());
    return e;
}

std::uint32_t u32(const std::uint8_t* p) {
    std::uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
}
std::uint16_t u16(const std::uint8_t* p) {
    std::uint16_t v;
    std::memcpy(&v, p, 2);
    return v;
}

// The GeoKeys and GDAL_METADATA GDAL's GTiff driver writes for `meta` and
// `bands` bands: read from the first directory of a 1x1 file it made.
std::vector<Entry> harvest_gdal_tags(const TiffMetadata& meta, int bands) {
    gdal::ensure_initialised();
    static std::atomic<unsigned> counter{0};
    const std::string mem = "/vsimem/overflight-tiff-tags-" + std::to_string(counter++) + ".tif";
    {
        gdal::Dataset ds(GDALCreate(GDALGetDriverByName("GTiff"), mem.c_str(), 1, 1, bands, GDT_Byte, nullptr));
        if (!ds) throw std::runtime_error("GDAL cannot create a GeoTIFF: " + gdal::last_error("GTiff"));
        if (meta.gt) {
            double g[6];
            std::copy(meta.gt->begin(), meta.gt->end(), g);
            GDALSetGeoTransform(ds.get(), g);
            if (!meta.wkt.empty() && GDALSetProjection(ds.get(), meta.wkt.c_str()) != CE_None)
                throw std::runtime_error("GDAL cannot state the CRS: " + gdal::last_error("bad WKT"));
        }
        if (meta.has_mapping)
            for (int b = 1; b <= bands; ++b) {
                GDALRasterBandH h = GDALGetRasterBand(ds.get(), b);
                GDALSetRasterScale(h, meta.scale);
                GDALSetRasterOffset(h, meta.offset);
                GDALSetRasterUnitType(h, "metre");
            }
    }
    vsi_l_offset size = 0;
    GByte* p = VSIGetMemFileBuffer(mem.c_str(), &size, TRUE);
    std::vector<std::uint8_t> file(p, p + size);
    CPLFree(p);
    std::vector<Entry> out;
    if (size < 8 || file[0] != 'I' || u16(&file[2]) != 42) throw std::runtime_error("GDAL wrote an unexpected GeoTIFF");
    const std::uint32_t ifd = u32(&file[4]);
    const std::uint16_t n = u16(&file[ifd]);
    for (std::uint16_t k = 0; k < n; ++k) {
        const std::uint8_t* e = &file[ifd + 2 + 12 * std::size_t(k)];
        const std::uint16_t tag = u16(e), type = u16(e + 2);
        if (tag != 34735 && tag != 34736 && tag != 34737 && tag != 42112) continue;
        Entry x{tag, type, u32(e + 4), {}};
        const std::size_t bytes = type_bytes(type) * x.count;
        const std::uint8_t* v = bytes <= 4 ? e + 8 : &file[u32(e + 8)];
        x.value.assign(v, v + bytes);
        out.push_back(std::move(x));
    }
    return out;
}

// harvest_gdal_tags, once per CRS, georeferencing presence, mapping and
// band count (a tiling run has a handful).
std::vector<Entry> gdal_tags(const TiffMetadata& meta, int bands) {
    using Key = std::tuple<std::string, bool, bool, double, double, int>;
    static std::mutex mutex;
    static std::map<Key, std::vector<Entry>> cache;
    const Key key{meta.wkt, meta.gt != nullptr, meta.has_mapping, meta.scale, meta.offset, bands};
    {
        std::lock_guard<std::mutex> lock(mutex);
        if (const auto it = cache.find(key); it != cache.end()) return it->second;
    }
    std::vector<Entry> tags = harvest_gdal_tags(meta, bands);
    std::lock_guard<std::mutex> lock(mutex);
    return cache.emplace(key, std::move(tags)).first->second;
}

// GDAL's georeferencing tags for a geotransform: pixel scale and tiepoint
// for a north-up grid, else the full model transformation.
void georeferencing_tags(const std::array<double, 6>& g, std::vector<Entry>& tags) {
    if (g[2] == 0 && g[4] == 0 && g[5] < 0) {
        tags.push_back(entry<double>(33550, kDouble, {g[1], -g[5], 0.0}));
        tags.push_back(entry<double>(33922, kDouble, {0.0, 0.0, 0.0, g[0], g[3], 0.0}));
    } else {
        tags.push_back(entry<double>(34264, kDouble,
                                     {g[1], g[2], 0.0, g[0], g[4], g[5], 0.0, g[3], 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0}));
    }
}

struct CompressorFree {
    void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};

// One band of `img` DEFLATE-compressed (zlib stream, TIFF compression 8),
// rows differenced first for integer samples (TIFF predictor 2).
void compress_band(const TiffImage& img, int b, std::vector<std::uint8_t>& scratch, std::vector<std::uint8_t>& out) {
    thread_local std::unique_ptr<libdeflate_compressor, CompressorFree> compressor(libdeflate_alloc_compressor(1));
    if (!compressor) throw std::runtime_error("out of memory for the DEFLATE compressor");
    const std::size_t plane = std::size_t(img.cols) * std::size_t(img.rows) * std::size_t(img.bytes);
    const auto* src = static_cast<const std::uint8_t*>(img.data) + std::size_t(b) * plane;
    const void* in = src;
    if (!img.is_float) {
        scratch.assign(src, src + plane);
        const std::size_t cols = std::size_t(img.cols);
        if (img.bytes == 1) {
            for (std::size_t i = 0; i < std::size_t(img.rows); ++i) {
                std::uint8_t* row = scratch.data() + i * cols;
                for (std::size_t j = cols - 1; j > 0; --j) row[j] = std::uint8_t(row[j] - row[j - 1]);
            }
        } else if (img.bytes == 2) {
            auto* z = reinterpret_cast<std::uint16_t*>(scratch.data());
            for (std::size_t i = 0; i < std::size_t(img.rows); ++i) {
                std::uint16_t* row = z + i * cols;
                for (std::size_t j = cols - 1; j > 0; --j) row[j] = std::uint16_t(row[j] - row[j - 1]);
            }
        } else {
            throw std::runtime_error("the encoder differences 8- and 16-bit integers only");
        }
        in = scratch.data();
    }
    out.resize(libdeflate_zlib_compress_bound(compressor.get(), plane));
    const std::size_t n = libdeflate_zlib_compress(compressor.get(), in, plane, out.data(), out.size());
    if (n == 0) throw std::runtime_error("DEFLATE output overflow");
    out.resize(n);
}

void put16(std::vector<std::uint8_t>& f, std::size_t at, std::uint16_t v) { std::memcpy(&f[at], &v, 2); }
void put32(std::vector<std::uint8_t>& f, std::size_t at, std::uint32_t v) { std::memcpy(&f[at], &v, 4); }

std::size_t even(std::size_t n) { return n + (n & 1); }

// Bytes of a directory of `tags` with the values that do not fit an entry.
std::size_t directory_bytes(const std::vector<Entry>& tags) {
    std::size_t n = 2 + 12 * tags.size() + 4;
    for (const Entry& e : tags)
        if (e.value.size() > 4) n += even(e.value.size());
    return n;
}

// Writes the directory of `tags` (sorted) at `at` of `f`, its long values
// after it, and `next` as the offset of the next directory.
void put_directory(std::vector<std::uint8_t>& f, std::size_t at, const std::vector<Entry>& tags, std::uint32_t next) {
    put16(f, at, std::uint16_t(tags.size()));
    std::size_t values = at + 2 + 12 * tags.size() + 4;
    for (std::size_t t = 0; t < tags.size(); ++t) {
        const Entry& e = tags[t];
        const std::size_t p = at + 2 + 12 * t;
        put16(f, p, e.tag);
        put16(f, p + 2, e.type);
        put32(f, p + 4, e.count);
        if (e.value.size() <= 4) {
            std::memcpy(&f[p + 8], e.value.data(), e.value.size());
        } else {
            put32(f, p + 8, std::uint32_t(values));
            std::memcpy(&f[values], e.value.data(), e.value.size());
            values += even(e.value.size());
        }
    }
    put32(f, at + 2 + 12 * tags.size(), next);
}

} // namespace

// The layout of GDAL's cloud-optimised GeoTIFFs: all directories first,
// then the strips from the smallest level to the full image, so that a
// truncated file loses the full image's samples (a reader fails on them)
// rather than reading whole and missing only a reduced level.
std::vector<std::uint8_t> encode_tiff(const std::vector<TiffImage>& images, const TiffMetadata& meta) {
    if (images.empty()) throw std::runtime_error("no image to encode");
    const int bands = images[0].bands;
    std::vector<Entry> file_tags;
    if (meta.gt) georeferencing_tags(*meta.gt, file_tags);
    if (meta.gt || meta.has_mapping) {
        std::vector<Entry> gdal = gdal_tags(meta, bands);
        file_tags.insert(file_tags.end(), gdal.begin(), gdal.end());
    }
    const std::size_t levels = images.size();
    std::vector<std::vector<std::vector<std::uint8_t>>> strips(levels);
    std::vector<std::uint8_t> scratch;
    for (std::size_t k = 0; k < levels; ++k) {
        strips[k].resize(std::size_t(images[k].bands));
        for (int b = 0; b < images[k].bands; ++b) compress_band(images[k], b, scratch, strips[k][std::size_t(b)]);
    }
    std::vector<std::vector<Entry>> dirs(levels);
    std::vector<std::size_t> dir_at(levels);
    std::size_t size = 8;
    for (std::size_t k = 0; k < levels; ++k) {
        const TiffImage& img = images[k];
        const auto spp = std::uint16_t(img.bands);
        std::vector<Entry>& tags = dirs[k];
        if (k > 0) tags.push_back(entry<std::uint32_t>(254, kLong, {1u})); // reduced-resolution image
        tags.push_back(entry<std::uint32_t>(256, kLong, {std::uint32_t(img.cols)}));
        tags.push_back(entry<std::uint32_t>(257, kLong, {std::uint32_t(img.rows)}));
        tags.push_back(entry<std::uint16_t>(258, kShort, std::vector<std::uint16_t>(spp, std::uint16_t(8 * img.bytes))));
        tags.push_back(entry<std::uint16_t>(259, kShort, {8})); // Adobe DEFLATE
        tags.push_back(entry<std::uint16_t>(262, kShort, {std::uint16_t(meta.rgb ? 2 : 1)}));
        tags.push_back(entry<std::uint32_t>(273, kLong, std::vector<std::uint32_t>(spp, 0u))); // placed below
        tags.push_back(entry<std::uint16_t>(277, kShort, {spp}));
        tags.push_back(entry<std::uint32_t>(278, kLong, {std::uint32_t(img.rows)}));
        std::vector<std::uint32_t> counts;
        for (const auto& s : strips[k]) counts.push_back(std::uint32_t(s.size()));
        tags.push_back(entry<std::uint32_t>(279, kLong, counts));
        tags.push_back(entry<std::uint16_t>(284, kShort, {std::uint16_t(spp > 1 ? 2 : 1)}));
        if (!img.is_float) tags.push_back(entry<std::uint16_t>(317, kShort, {2}));
        if (meta.rgb && spp == 4) tags.push_back(entry<std::uint16_t>(338, kShort, {2})); // unassociated alpha
        tags.push_back(entry<std::uint16_t>(339, kShort, std::vector<std::uint16_t>(spp, std::uint16_t(img.is_float ? 3 : 1))));
        if (k == 0) tags.insert(tags.end(), file_tags.begin(), file_tags.end());
        std::sort(tags.begin(), tags.end(), [](const Entry& a, const Entry& b) { return a.tag < b.tag; });
        dir_at[k] = size;
        size += directory_bytes(tags);
    }
    for (std::size_t k = levels; k-- > 0;) {
        Entry& offsets = *std::find_if(dirs[k].begin(), dirs[k].end(), [](const Entry& e) { return e.tag == 273; });
        for (std::size_t b = 0; b < strips[k].size(); ++b) {
            const auto at = std::uint32_t(size);
            std::memcpy(offsets.value.data() + 4 * b, &at, 4);
            size += even(strips[k][b].size());
        }
    }
    std::vector<std::uint8_t> f(size, 0);
    f[0] = f[1] = 'I';
    f[2] = 42;
    put32(f, 4, std::uint32_t(dir_at[0]));
    for (std::size_t k = 0; k < levels; ++k) {
        put_directory(f, dir_at[k], dirs[k], k + 1 < levels ? std::uint32_t(dir_at[k + 1]) : 0u);
        const Entry& offsets = *std::find_if(dirs[k].begin(), dirs[k].end(), [](const Entry& e) { return e.tag == 273; });
        for (std::size_t b = 0; b < strips[k].size(); ++b)
            std::memcpy(&f[u32(offsets.value.data() + 4 * b)], strips[k][b].data(), strips[k][b].size());
    }
    return f;
}

} // namespace overflight
