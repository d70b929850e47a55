#include "io/FlightRecordFile.h"

#include "core/Error.h"
#include "io/Files.h"

#include <cstdio>
#include <string_view>

namespace overflight {

FlightRecord read_flight_record(const std::string& path) {
    const std::vector<std::uint8_t> bytes = read_file_bytes(path);
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    return parse_flight_record(text, path);
}

void write_flight_record(const std::string& path, const FlightRecord& record) {
    const std::string text = format_flight_record(record);
    write_atomically(path, [&](const std::string& temp) {
        std::FILE* f = std::fopen(temp.c_str(), "wb");
        if (!f) throw Error(path, "cannot create the file");
        const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
        const bool closed = std::fclose(f) == 0;
        if (!written || !closed) throw Error(path, "write failed (disk full?)");
    });
}

} // namespace overflight
