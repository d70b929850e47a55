#include "io/TileParts.h"

#include "core/Error.h"
#include "io/Files.h"
#include "io/TileFiles.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <map>

namespace fs = std::filesystem;

namespace overflight {

using json = nlohmann::json;

namespace {

std::string record_name(TilePart p, const char* suffix) {
    return "." + std::string(kPartPrefix) + std::to_string(p.index) + "-of-" + std::to_string(p.count) + suffix;
}

std::string record_path(const std::string& dir, TilePart p, const char* suffix) {
    return (fs::path(dir) / record_name(p, suffix)).string();
}

int positive(const std::string& s, const std::string& text) {
    if (s.empty() || s.size() > 5 || !std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; }))
        throw Error("--part", "'" + text + "' is not K/N with whole numbers 1 <= K <= N <= 65536");
    return std::stoi(s);
}

// The record of part `p` in `dir`, checked against the index it is merged into.
PartRecord read_record(const std::string& dir, TilePart p, const TileIndex& ix) {
    const std::string path = record_path(dir, p, ".json");
    PartRecord rec;
    rec.part = p;
    try {
        const std::vector<std::uint8_t> bytes = read_file_bytes(path);
        const json j = json::parse(bytes.begin(), bytes.end());
        rec.checksum = j.at("checksum").get<std::string>();
        rec.first_row = j.at("rows").at(0).get<int>();
        rec.end_row = j.at("rows").at(1).get<int>();
        rec.min_height = j.at("min_height").get<std::vector<float>>();
        rec.max_height = j.at("max_height").get<std::vector<float>>();
        rec.roughness = j.at("roughness").get<std::vector<std::vector<float>>>();
        if (j.at("tile_size").get<int>() != ix.grid.tile_size) throw Error(path, "was written for another tile size");
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(path, std::string("malformed part record: ") + e.what());
    }
    if (rec.checksum != ix.checksum) throw Error(path, "was written for another source; run that part again");
    const auto [first, end] = part_tile_rows(ix.grid.tile_rows, p);
    const std::size_t n = std::size_t(end - first) * std::size_t(ix.grid.tile_cols);
    if (rec.first_row != first || rec.end_row != end || rec.min_height.size() != n || rec.max_height.size() != n ||
        rec.roughness.size() != (ix.levels > 0 ? n : 0))
        throw Error(path, "does not hold the tiles of part " + std::to_string(p.index) + " of " + std::to_string(p.count));
    if (ix.overview_stride > 1) {
        const std::string ov = record_path(dir, p, ".overview");
        const std::vector<std::uint8_t> bytes = read_file_bytes(ov);
        std::tie(rec.overview_first, rec.overview_end) = part_overview_rows(ix, first, end);
        const std::size_t m = std::size_t(rec.overview_end - rec.overview_first) * std::size_t(ix.overview_cols);
        if (bytes.size() != 5 * m) throw Error(ov, "does not hold the overview rows of its part");
        rec.overview_heights.resize(m);
        for (std::size_t i = 0; i < m; ++i)
            rec.overview_heights[i] = std::uint16_t(bytes[2 * i] | (bytes[2 * i + 1] << 8));
        rec.overview_rgb.assign(bytes.begin() + std::ptrdiff_t(2 * m), bytes.end());
    }
    return rec;
}

// The part counts N for which `dir` holds some record.
std::vector<int> record_counts(const std::string& dir) {
    std::vector<int> counts;
    std::error_code ec;
    const std::string prefix = "." + std::string(kPartPrefix);
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        const std::size_t of = name.find("-of-");
        if (name.rfind(prefix, 0) != 0 || of == std::string::npos || name.size() < 5 ||
            name.compare(name.size() - 5, 5, ".json") != 0)
            continue;
        const std::string n = name.substr(of + 4, name.size() - 5 - of - 4);
        if (!n.empty() && std::all_of(n.begin(), n.end(), [](char c) { return c >= '0' && c <= '9'; }) && n.size() < 6)
            counts.push_back(std::stoi(n));
    }
    std::sort(counts.begin(), counts.end());
    counts.erase(std::unique(counts.begin(), counts.end()), counts.end());
    return counts;
}

} // namespace

TilePart parse_tile_part(const std::string& text) {
    const std::size_t slash = text.find('/');
    if (slash == std::string::npos) throw Error("--part", "'" + text + "' is not K/N (e.g. 2/3)");
    TilePart p{positive(text.substr(0, slash), text), positive(text.substr(slash + 1), text)};
    if (p.index < 1 || p.count > 65536 || p.index > p.count)
        throw Error("--part", "'" + text + "' is not K/N with whole numbers 1 <= K <= N <= 65536");
    return p;
}

std::pair<int, int> part_tile_rows(int tile_rows, TilePart part) {
    const auto at = [&](int k) { return int(std::int64_t(tile_rows) * k / part.count); };
    return {at(part.index - 1), at(part.index)};
}

std::pair<int, int> part_overview_rows(const TileIndex& ix, int first_row, int end_row) {
    const int f = ix.overview_stride, s = ix.grid.stride();
    const auto owner = [&](int i) {
        const std::int64_t source_row = std::min<std::int64_t>(std::int64_t(i) * f, ix.grid.source_rows - 1);
        return int(std::min<std::int64_t>(source_row / s, ix.grid.tile_rows - 1));
    };
    int first = 0;
    while (first < ix.overview_rows && owner(first) < first_row) ++first;
    int end = first;
    while (end < ix.overview_rows && owner(end) < end_row) ++end;
    return {first, end};
}

void write_part_record(const std::string& dir, const PartRecord& rec) {
    {
        // Written even when empty (a part without overview rows, or no
        // overview), so that a record is always whole.
        std::vector<std::uint8_t> bytes(2 * rec.overview_heights.size());
        for (std::size_t i = 0; i < rec.overview_heights.size(); ++i) {
            bytes[2 * i] = std::uint8_t(rec.overview_heights[i] & 0xff);
            bytes[2 * i + 1] = std::uint8_t(rec.overview_heights[i] >> 8);
        }
        bytes.insert(bytes.end(), rec.overview_rgb.begin(), rec.overview_rgb.end());
        write_file_atomically(record_path(dir, rec.part, ".overview"), bytes.data(), bytes.size());
    }
    const json j{{"part", rec.part.index},
                 {"parts", rec.part.count},
                 {"checksum", rec.checksum},
                 {"tile_size", rec.tile_size},
                 {"rows", {rec.first_row, rec.end_row}},
                 {"min_height", rec.min_height},
                 {"max_height", rec.max_height},
                 {"roughness", rec.roughness}};
    const std::string text = j.dump() + "\n";
    write_file_atomically(record_path(dir, rec.part, ".json"), text.data(), text.size());
}

std::pair<TileIndex, bool> merge_tile_parts(const std::string& dir, int parts, bool required) {
    const std::string ipath = index_path(dir);
    std::error_code ec;
    if (!fs::is_regular_file(ipath, ec)) throw Error(ipath, "missing (not a tile directory)");
    const std::vector<std::uint8_t> bytes = read_file_bytes(ipath);
    TileIndex ix = parse_tile_index(std::string(bytes.begin(), bytes.end()), ipath);
    if (parts == 0) {
        // The N whose records were written for this index's source.
        for (const int n : record_counts(dir)) {
            const std::string first = record_path(dir, TilePart{1, n}, ".json");
            try {
                const std::vector<std::uint8_t> b = read_file_bytes(first);
                if (json::parse(b.begin(), b.end()).at("checksum") == ix.checksum) parts = n;
            } catch (const std::exception&) {
            }
        }
        if (parts == 0) {
            if (ix.complete) return {ix, true}; // tiled whole, nothing to merge
            throw Error(dir, "holds no part records of this tiling (run `overflight tile --part K/N` first)");
        }
    }
    std::vector<int> missing;
    for (int k = 1; k <= parts; ++k)
        if (!fs::is_regular_file(record_path(dir, TilePart{k, parts}, ".json"), ec)) missing.push_back(k);
    if (!missing.empty()) {
        if (!required) return {ix, false};
        std::string list;
        for (std::size_t i = 0; i < missing.size() && i < 10; ++i) list += (i ? ", " : "") + std::to_string(missing[i]);
        if (missing.size() > 10) list += ", ...";
        throw Error(dir, std::to_string(missing.size()) + " of " + std::to_string(parts) + " parts not finished (" + list +
                             "); run them with --part K/" + std::to_string(parts));
    }
    TileGrid& g = ix.grid;
    const std::size_t total = g.exists.size();
    std::vector<std::vector<float>> roughness(ix.levels > 0 ? total : 0);
    std::vector<std::uint16_t> ov_heights;
    std::vector<std::uint8_t> ov_rgb;
    const std::size_t ov_n = std::size_t(ix.overview_rows) * std::size_t(ix.overview_cols);
    if (ix.overview_stride > 1) {
        ov_heights.resize(ov_n);
        ov_rgb.resize(3 * ov_n);
    }
    for (int k = 1; k <= parts; ++k) {
        const PartRecord rec = read_record(dir, TilePart{k, parts}, ix);
        const std::size_t at = std::size_t(rec.first_row) * std::size_t(g.tile_cols);
        std::copy(rec.min_height.begin(), rec.min_height.end(), g.min_height.begin() + std::ptrdiff_t(at));
        std::copy(rec.max_height.begin(), rec.max_height.end(), g.max_height.begin() + std::ptrdiff_t(at));
        for (std::size_t i = 0; i < rec.roughness.size(); ++i) roughness[at + i] = rec.roughness[i];
        if (ix.overview_stride > 1) {
            const std::size_t o = std::size_t(rec.overview_first) * std::size_t(ix.overview_cols);
            const std::size_t m = rec.overview_heights.size();
            std::copy(rec.overview_heights.begin(), rec.overview_heights.end(), ov_heights.begin() + std::ptrdiff_t(o));
            for (int b = 0; b < 3; ++b)
                std::copy_n(rec.overview_rgb.begin() + std::ptrdiff_t(b * m), m,
                            ov_rgb.begin() + std::ptrdiff_t(b * ov_n + o));
        }
    }
    if (ix.overview_stride > 1) {
        Terrain o(ix.overview_rows, ix.overview_cols, g.h_scale * float(ix.overview_stride), g.v_scale, g.y_offset);
        o.heights() = std::move(ov_heights);
        for (std::size_t i = 0; i < ov_n; ++i) o.colors()[i] = Rgb8{ov_rgb[i], ov_rgb[ov_n + i], ov_rgb[2 * ov_n + i]};
        write_overview(dir, ix, o, true);
    } else {
        fs::remove(fs::path(dir) / kOverviewHeights, ec); // left over from a larger source
        fs::remove(fs::path(dir) / kOverviewColors, ec);
    }
    g.roughness = std::move(roughness);
    g.max_level = ix.levels;
    ix.complete = true;
    write_index(dir, ix);
    return {ix, true};
}

} // namespace overflight
