// assign_on_huge_pages: the contents of vector::assign, storage kept when it
// suffices; HugePageAllocator: whole aligned huge pages; and, where the
// kernel offers transparent huge pages on advice, both backed by them;
// Image2D's storage (ImageAllocator): on a cache line, large images advised.
#include "core/HugePages.h"
#include "core/Image.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace overflight {
namespace {

// The kernel's transparent huge page mode ("always", "madvise", "never"),
// or "" where it has none.
std::string thp_mode() {
    std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string word;
    while (in >> word)
        if (word.size() > 2 && word.front() == '[') return word.substr(1, word.size() - 2);
    return "";
}

// AnonHugePages of the mapping of this process that holds p, in KiB.
long huge_kib_at(const void* p) {
    std::ifstream in("/proc/self/smaps");
    const auto at = reinterpret_cast<std::uintptr_t>(p);
    bool inside = false;
    for (std::string line; std::getline(in, line);) {
        std::uintptr_t lo = 0, hi = 0;
        char dash = 0;
        std::istringstream range(line);
        if (range >> std::hex >> lo >> dash >> hi && dash == '-') {
            inside = lo <= at && at < hi;
            continue;
        }
        long kib = 0;
        if (inside && std::sscanf(line.c_str(), "AnonHugePages: %ld kB", &kib) == 1) return kib;
    }
    return 0;
}

TEST(HugePages, AssignFillsAndKeepsStorageThatSuffices) {
    std::vector<std::uint32_t> v;
    assign_on_huge_pages(v, 5, 7u);
    EXPECT_EQ(v, (std::vector<std::uint32_t>{7, 7, 7, 7, 7}));
    const std::uint32_t* before = v.data();
    assign_on_huge_pages(v, 3, 9u);
    EXPECT_EQ(v, (std::vector<std::uint32_t>{9, 9, 9}));
    EXPECT_EQ(v.data(), before);
    assign_on_huge_pages(v, 1000, 2u);
    ASSERT_EQ(v.size(), 1000u);
    for (const std::uint32_t x : v) ASSERT_EQ(x, 2u);
}

TEST(HugePages, LargeStorageIsBackedByHugePagesWhereTheKernelOffersThem) {
    std::vector<std::uint64_t> v;
    assign_on_huge_pages(v, std::size_t(32) << 17, std::uint64_t(1)); // 32 MiB
    const std::string mode = thp_mode();
    if (mode != "always" && mode != "madvise") {
        std::printf("transparent huge pages: \"%s\" here, so 4 KiB pages serve\n", mode.c_str());
        return;
    }
    // All but the partial 2 MiB pages at either end can be huge.
    EXPECT_GE(huge_kib_at(v.data() + v.size() / 2), 16 * 1024) << "mode " << mode;
}

TEST(HugePages, AllocatorGivesWholeAlignedHugePages) {
    std::vector<std::uint32_t, HugePageAllocator<std::uint32_t>> v(1000, 5u); // 4 KB: one 2 MiB page
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % (std::uintptr_t(2) << 20), 0u);
    for (const std::uint32_t x : v) ASSERT_EQ(x, 5u);
    v.resize(std::size_t(3) << 20, 6u); // 12 MiB: reallocated, the contents kept
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % (std::uintptr_t(2) << 20), 0u);
    EXPECT_EQ(v[999], 5u);
    EXPECT_EQ(v.back(), 6u);
    const std::string mode = thp_mode();
    if (mode != "always" && mode != "madvise") {
        std::printf("transparent huge pages: \"%s\" here, so 4 KiB pages serve\n", mode.c_str());
        return;
    }
    // All but one of its 6 pages (a sanitizer's allocator writes its own
    // header into the first before the advice).
    EXPECT_GE(huge_kib_at(v.data()), 10 * 1024) << "mode " << mode;
}

// The renderers rely on it: a block of 32 columns at a width that is a
// multiple of 16 then writes whole depth lines (FloatingHorizonShear).
TEST(HugePages, ImagesStartACacheLine) {
    for (const int w : {1, 3, 1366, 3840}) {
        const ColorImage color(w, 7);
        const DepthImage depth(w, 2160);
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(color.pixels.data()) % 64, 0u) << w;
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(depth.pixels.data()) % 64, 0u) << w;
        EXPECT_EQ(depth.at(w - 1, 2159), 0.0f);
    }
    DepthImage grown;
    grown.resize(4, 4, 1.0f);
    grown.resize(3840, 2160, 0.5f);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(grown.pixels.data()) % 64, 0u);
    EXPECT_EQ(grown.at(3839, 2159), 0.5f);
}

} // namespace
} // namespace overflight
