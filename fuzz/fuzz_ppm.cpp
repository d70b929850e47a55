// libFuzzer harness for the PPM color-map parser (CMSC 23700 project 2a, sec. 6.3).
#include "core/Error.h"
#include "io/Pnm.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        const overflight::ColorImage c = overflight::parse_ppm(data, size, "fuzz.ppm");
        volatile std::uint8_t sink = c.pixels.empty() ? 0 : c.pixels.back().g;
        (void)sink;
    } catch (const overflight::Error&) {
    }
    return 0;
}
