#pragma once
// Reading and writing the flight record CSV of sim/FlightRecord.h
// (`fly --record path.csv`, `fly --replay path.csv`). The format itself lives
// in the sim layer; this is only the file side, so that sim stays I/O-free.
#include "sim/FlightRecord.h"

#include <string>

namespace overflight {

// Throws Error(path, ...) when the file is missing or unreadable, or when its
// content is not a flight record (the parse errors name the line).
FlightRecord read_flight_record(const std::string& path);

// Writes the record atomically (temporary name + rename): on failure nothing is
// left at `path` and an existing file there is untouched. Throws Error(path, ...).
void write_flight_record(const std::string& path, const FlightRecord& record);

} // namespace overflight
