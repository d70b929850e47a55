// libFuzzer harness for the USGS DEM Record A reader (USGS DEM Standards
// Part 2, Record A): any bytes must give fields or nothing, never crash, and
// the declared profile count must agree with the USGS_PROFILES field.
#include "io/UsgsDemHeader.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    const auto fields = overflight::usgs_record_a(text);
    const long profiles = overflight::usgs_profile_count(text);
    std::string listed;
    for (const auto& [key, value] : fields)
        if (key == "USGS_PROFILES") listed = value;
    if (profiles >= 0 && listed != std::to_string(profiles)) std::abort();
    if (overflight::usgs_minimum_file_size(profiles) < 864) std::abort();
    return 0;
}
