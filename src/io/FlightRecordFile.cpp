#include "io/FlightRecordFile.h"

#include "core/Error.h"
#include "io/Files.h"

#include <string_view>

namespace overflight {

FlightRecord read_flight_record(const std::string& path) {
    const std::vector<std::uint8_t> bytes = read_file_bytes(path);
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    return parse_flight_record(text, path);
}

void write_flight_record(const std::string& path, const FlightRecord& record) {
    const std::string text = format_flight_record(record);
    write_file_atomically(path, [&](CheckedFile& file) { file.write(text.data(), text.size()); });
}

} // namespace overflight
