// libFuzzer harness for the `map` TOML parser (CMSC 23700 project 2a, sec. 6.1; DESIGN sec.
// 4, 5): any text must parse or throw overflight::Error, and what parses must
// format and parse back.
#include "core/Error.h"
#include "io/MapFile.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    overflight::MapFile map;
    try {
        map = overflight::parse_map(text, "fuzz/map", "fuzz");
    } catch (const overflight::Error&) {
        return 0;
    }
    // Round trip: what we accept we must be able to write and read again.
    const overflight::MapFile back = overflight::parse_map(overflight::format_map(map), "fuzz/map2", "");
    if (back.scene.objects.size() != map.scene.objects.size() || back.scene.lines.size() != map.scene.lines.size())
        std::abort();
    return 0;
}
