// libFuzzer harness for `--scene` files (DESIGN sec. 5): any text must parse
// or throw overflight::Error, and the objects and lines that parse must be
// written by format_map and read back unchanged in number.
#include "core/Error.h"
#include "io/MapFile.h"
#include "io/SceneFile.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    overflight::MapFile map;
    try {
        map.scene = overflight::parse_scene(text, "fuzz/scene", "fuzz");
    } catch (const overflight::Error&) {
        return 0;
    }
    const overflight::MapFile back = overflight::parse_map(overflight::format_map(map), "fuzz/map", "");
    if (back.scene.objects.size() != map.scene.objects.size() || back.scene.lines.size() != map.scene.lines.size())
        std::abort();
    for (std::size_t i = 0; i < map.scene.objects.size(); ++i)
        if (back.scene.objects[i].color != map.scene.objects[i].color) std::abort();
    return 0;
}
