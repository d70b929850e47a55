// Based on: S. Macke, "Voxel Space"; A. LaMothe, "Tricks of the
// Game-Programming Gurus". See ClassicBench.h.
#include "ClassicBench.h"

#include "raycast/ClassicVoxelSpace.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace overflight::app {

namespace {

// The originals' step grows with distance; 0.5 % per line takes 485 lines to
// 2048 samples instead of 2048.
constexpr double kClassicGrowth = 1.005;

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n == 0 ? 0.0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

const nlohmann::json* find_run(const nlohmann::json& runs, const std::string& method) {
    for (const auto& r : runs)
        if (r["method"] == method) return &r;
    return nullptr;
}

} // namespace

nlohmann::json classic_voxel_space_bench(const Terrain& terrain, const Camera& camera, int frames) {
    struct Schedule {
        const char* name;
        double growth;
        std::vector<double> ms;
        ClassicVoxelSpaceStats stats;
    };
    Schedule schedules[] = {{"classic (1-sample step)", 1.0, {}, {}}, {"classic (growing step)", kClassicGrowth, {}, {}}};
    ColorImage color;
    for (int f = -1; f < frames; ++f) // frame -1: warm-up
        for (Schedule& s : schedules) {
            ClassicVoxelSpaceOptions options;
            options.step_growth = s.growth;
            const auto t0 = std::chrono::steady_clock::now();
            s.stats = render_classic_voxel_space(terrain, camera, options, color);
            const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
            if (f >= 0) s.ms.push_back(ms);
        }
    nlohmann::json rows = nlohmann::json::array();
    for (const Schedule& s : schedules) {
        const double med = median(s.ms);
        rows.push_back({{"method", s.name},
                        {"width", camera.width},
                        {"height", camera.height},
                        {"frames", int(s.ms.size())},
                        {"ms_median", med},
                        {"ms_min", *std::min_element(s.ms.begin(), s.ms.end())},
                        {"fps", 1000.0 / med},
                        {"step_growth", s.growth},
                        {"samples", double(s.stats.samples)},
                        {"samples_per_column", s.stats.lines},
                        {"ns_per_sample", med * 1e6 / double(s.stats.samples)}});
    }
    return rows;
}

void print_classic_comparison(const nlohmann::json& runs, int threads) {
    const nlohmann::json* voxel = find_run(runs, "voxel");
    if (!voxel || !voxel->contains("ns_per_sample")) return;
    auto per_core = [&](const nlohmann::json& r) {
        return r["ns_per_sample"].get<double>() * (r["method"] == "voxel-literal" ? 1 : threads);
    };
    const double base = per_core(*voxel);
    std::printf("\nThe Floating Horizon beside the classic Voxel Space loop (no depth, nearest sample), same view\n\n"
                "| renderer | ms (median) | fps | samples per column | ns / sample / core | x voxel per sample |\n"
                "|---|---:|---:|---:|---:|---:|\n");
    for (const char* name : {"voxel", "voxel-literal", "classic (1-sample step)", "classic (growing step)"}) {
        const nlohmann::json* r = find_run(runs, name);
        if (!r || !r->contains("ns_per_sample")) continue;
        const double med = (*r)["ms_median"].get<double>();
        const double columns = double((*r)["width"].get<int>());
        const double per_column = r->contains("samples_per_column") ? (*r)["samples_per_column"].get<double>()
                                                                    : (*r)["samples"].get<double>() / columns;
        std::printf("| %s | %.2f | %.1f | %.0f | %.2f | %.2f |\n", name, med, 1000.0 / med, per_column, per_core(*r),
                    per_core(*r) / base);
    }
}

} // namespace overflight::app
