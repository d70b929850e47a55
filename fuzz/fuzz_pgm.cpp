// libFuzzer harness for the 16-bit PGM parser of hovercraft height fields
// (CMSC 23700 project 2a, sec. 6.2): any input must parse or throw overflight::Error, never
// crash, read out of bounds or allocate beyond the input's size.
#include "core/Error.h"
#include "io/Pnm.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        const overflight::GrayImage16 g = overflight::parse_pgm(data, size, "fuzz.pgm");
        // Touch the result so the parse cannot be optimised away.
        volatile std::uint16_t sink = g.image.pixels.empty() ? 0 : g.image.pixels.back();
        (void)sink;
    } catch (const overflight::Error&) {
    }
    return 0;
}
