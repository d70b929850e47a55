// libFuzzer harness for a tile directory's index.json parser
// (io/TileIndex.h): any text must parse or throw overflight::Error, without
// allocating more than the text backs or hanging on a declared size, and what
// parses must be a valid index that writes and parses back unchanged.
#include "core/Error.h"
#include "io/TileIndex.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    overflight::TileIndex index;
    try {
        index = overflight::parse_tile_index(text, "fuzz/index.json");
    } catch (const overflight::Error&) {
        return 0;
    }
    const std::string written = overflight::tile_index_text(index);
    if (overflight::tile_index_text(overflight::parse_tile_index(written, "fuzz/index2.json")) != written) std::abort();
    return 0;
}
