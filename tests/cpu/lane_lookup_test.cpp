// The AVX2 kernels' table lookups (LaneLookup.h): gathers, scalar loads and
// windows permuted in registers read the same entries, whether the lanes fall
// in the window (neighbours either side of lane 0, at the table's ends) or
// not (a lane just before or after it, a far one, a table shorter than it).
#if defined(__x86_64__) && defined(__GNUC__)
#include "raycast/LaneLookup.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

using namespace overflight;

namespace {

using Lanes = std::array<std::int32_t, 8>;

// table[idx[q]] of each lane through L, as words and as floats; with a mask,
// the masked-out lanes' idx is not read and they come back 0.
template <class L>
__attribute__((target("avx2"))) Lanes words(const std::vector<std::uint32_t>& table, const Lanes& idx) {
    Lanes out;
    const __m256i i = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(idx.data()));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out.data()), L::words(table.data(), int(table.size()), i));
    return out;
}
template <class L>
__attribute__((target("avx2"))) Lanes floats(const std::vector<float>& table, const Lanes& idx) {
    Lanes out;
    const __m256i i = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(idx.data()));
    _mm256_storeu_ps(reinterpret_cast<float*>(out.data()), L::floats(table.data(), int(table.size()), i));
    return out;
}
template <class L>
__attribute__((target("avx2"))) Lanes masked(const std::vector<std::uint32_t>& table, const Lanes& idx,
                                             const Lanes& mask) {
    Lanes out;
    const __m256i i = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(idx.data()));
    const __m256i m = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(mask.data()));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out.data()), L::words(table.data(), int(table.size()), i, m));
    return out;
}

std::string show(const Lanes& v) {
    std::string s;
    for (std::int32_t x : v) s += std::to_string(x) + " ";
    return s;
}

} // namespace

TEST(LaneLookup, EveryWayReadsTheSameEntries) {
    if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "no AVX2 on this CPU";
    // Entries that tell their index apart from any other's, as words and as float bits.
    std::vector<std::uint32_t> table(40);
    std::vector<float> ftable(40);
    for (std::size_t e = 0; e < table.size(); ++e) {
        table[e] = 0xA5000000u + std::uint32_t(e) * 0x10101u;
        ftable[e] = 0.5f + float(e) * 1.25f;
    }
    const std::vector<std::uint32_t> short_table(table.begin(), table.begin() + 7);
    // Lane 0 at 20: the window is entries 17..24.
    const std::vector<Lanes> cases = {
        {20, 20, 20, 20, 20, 20, 20, 20}, // one entry
        {20, 21, 22, 23, 24, 24, 23, 22}, // climbing from lane 0 to the window's last
        {20, 19, 18, 17, 17, 18, 19, 20}, // 3 before lane 0: the window's first entry
        {20, 17, 24, 21, 18, 23, 22, 19}, // every entry of the window
        {20, 20, 16, 20, 20, 20, 20, 20}, // 4 before lane 0: outside the window
        {20, 20, 20, 20, 20, 20, 20, 25}, // 5 after lane 0: outside the window
        {0, 1, 0, 2, 5, 7, 6, 3},         // at the table's start (the window clamped to 0..7)
        {39, 38, 32, 35, 39, 33, 37, 36}, // at its end (clamped to 32..39)
        {39, 31, 39, 39, 39, 39, 39, 39}, // one before the clamped window
        {2, 39, 0, 1, 2, 3, 4, 5},        // far apart
    };
    for (const Lanes& idx : cases) {
        Lanes expect, expect_f;
        for (int q = 0; q < 8; ++q) {
            expect[std::size_t(q)] = std::int32_t(table[std::size_t(idx[std::size_t(q)])]);
            std::memcpy(&expect_f[std::size_t(q)], &ftable[std::size_t(idx[std::size_t(q)])], 4);
        }
        EXPECT_EQ(words<GatherLookup>(table, idx), expect) << show(idx);
        EXPECT_EQ(words<LoadLookup>(table, idx), expect) << show(idx);
        EXPECT_EQ(words<WindowLookup<LoadLookup>>(table, idx), expect) << show(idx);
        EXPECT_EQ(words<WindowLookup<GatherLookup>>(table, idx), expect) << show(idx);
        EXPECT_EQ(floats<WindowLookup<LoadLookup>>(ftable, idx), expect_f) << show(idx);
        // A table shorter than the window is read through the fallback.
        bool in_short = true;
        for (std::int32_t i : idx) in_short = in_short && i < 7;
        if (in_short) {
            Lanes expect_short;
            for (int q = 0; q < 8; ++q)
                expect_short[std::size_t(q)] = std::int32_t(short_table[std::size_t(idx[std::size_t(q)])]);
            EXPECT_EQ(words<WindowLookup<LoadLookup>>(short_table, idx), expect_short) << show(idx);
        }
    }
    // Masked lanes: their indices (here past the table, or before it) are not
    // read, and they come back 0; lane 0 masked (the fallback) or not (the window).
    const std::vector<std::pair<Lanes, Lanes>> masked_cases = {
        {{1000, 21, -5, 22, 1 << 30, 20, 19, 23}, {0, -1, 0, -1, 0, -1, -1, -1}},
        {{20, 1000, 21, -5, 22, 1 << 30, 19, 23}, {-1, 0, -1, 0, -1, 0, -1, -1}},
    };
    for (const auto& [idx, mask] : masked_cases) {
        Lanes expect;
        for (int q = 0; q < 8; ++q)
            expect[std::size_t(q)] = mask[std::size_t(q)] ? std::int32_t(table[std::size_t(idx[std::size_t(q)])]) : 0;
        EXPECT_EQ(masked<GatherLookup>(table, idx, mask), expect) << show(idx);
        EXPECT_EQ(masked<LoadLookup>(table, idx, mask), expect) << show(idx);
        EXPECT_EQ(masked<WindowLookup<LoadLookup>>(table, idx, mask), expect) << show(idx);
    }
}
#endif
