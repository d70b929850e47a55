// libFuzzer harness for the flight record CSV reader (sim/FlightRecord.h,
// read by `fly --replay`): any text must parse or throw overflight::Error
// with a one-line message, and what parses must format and parse back to the
// same record, bit for bit (the format writes shortest round-trip numbers).
#include "core/Error.h"
#include "sim/FlightRecord.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    overflight::FlightRecord record;
    try {
        record = overflight::parse_flight_record(text, "fuzz.csv");
    } catch (const overflight::Error& e) {
        if (std::string_view(e.what()).find('\n') != std::string_view::npos) std::abort();
        return 0;
    }
    if (record.frames.empty()) std::abort(); // "no frames" is an error
    const overflight::FlightRecord back =
        overflight::parse_flight_record(overflight::format_flight_record(record), "fuzz2.csv");
    if (!(back == record)) std::abort();
    return 0;
}
