// The flight record CSV (sim/FlightRecord.h) and its file side
// (io/FlightRecordFile.h).
#include "TestSupport.h"
#include "core/Error.h"
#include "io/FlightRecordFile.h"
#include "sim/FlightRecord.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace overflight;

namespace {
FlightRecord sample_record() {
    FlightRecord r;
    for (int i = 0; i < 3; ++i) {
        FlightFrame f;
        f.frame = i;
        f.time = i / 60.0;
        f.eye = {1.0 / 3.0 + i, 100.125, -0.1 * i};
        f.heading = 359.99999999999994;
        f.pitch = -5.4321e-7;
        f.x = 12.5;
        f.z = 1e-300;
        f.velocity = 11.2 * i;
        f.vehicle_heading = 0.75;
        f.keys = Controls{i == 0, i == 1, i == 2, i != 1};
        r.frames.push_back(f);
    }
    return r;
}
} // namespace

TEST(FlightRecord, FormatIsTheDocumentedCsv) {
    FlightRecord r;
    FlightFrame f;
    f.frame = 4;
    f.time = 0.5;
    f.eye = {1, 2.5, 3};
    f.heading = 90;
    f.pitch = -10;
    f.x = 7;
    f.z = 8;
    f.velocity = 0.25;
    f.vehicle_heading = 91;
    f.keys.accelerate = true;
    f.keys.right = true;
    r.frames.push_back(f);
    EXPECT_EQ(format_flight_record(r),
              "frame,time,eye_x,eye_y,eye_z,heading,pitch,x,z,velocity,vehicle_heading,accelerate,brake,left,right\n"
              "4,0.5,1,2.5,3,90,-10,7,8,0.25,91,1,0,0,1\n");
}

TEST(FlightRecord, RoundTripIsExact) {
    const FlightRecord r = sample_record();
    EXPECT_EQ(parse_flight_record(format_flight_record(r), "mem"), r);
    // Comments, blank lines and CRLF line ends are accepted.
    std::string text = "# recorded by a test\n\n" + format_flight_record(r);
    std::string crlf;
    for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    EXPECT_EQ(parse_flight_record(crlf, "mem"), r);
}

TEST(FlightRecord, BadInputNamesTheSourceAndLine) {
    const std::string header = std::string(flight_record_header()) + "\n";
    struct Case { std::string text, needle; };
    for (const Case& c : {Case{"", "empty"},
                          Case{"frame,time\n", "line 1"},
                          Case{header, "no frames"},
                          Case{header + "0,0,1,2,3,4,5,6,7,8,9,1,0,0\n", "line 2: 14 columns"},
                          Case{header + "0,0,1,2,x,4,5,6,7,8,9,1,0,0,0\n", "eye_z 'x'"},
                          Case{header + "0,0,1,2,nan,4,5,6,7,8,9,1,0,0,0\n", "eye_z"},
                          Case{header + "0,0,1,2,3,4,5,6,7,8,9,2,0,0,0\n", "accelerate must be 0 or 1"},
                          Case{header + "0,0,1,2,3,4,90,6,7,8,9,1,0,0,0\n", "line 2: pitch 90.000000 is outside"},
                          Case{header + "1,0,1,2,3,4,5,6,7,8,9,1,0,0,0\n1,0,1,2,3,4,5,6,7,8,9,1,0,0,0\n",
                               "line 3: frame 1 is not after"}}) {
        SCOPED_TRACE(c.text);
        try {
            parse_flight_record(c.text, "flight.csv");
            ADD_FAILURE() << "accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.subject(), "flight.csv");
            EXPECT_NE(e.problem().find(c.needle), std::string::npos) << e.problem();
        }
    }
}

TEST(FlightRecordFile, WritesAtomicallyAndReadsBack) {
    test::ScratchDir dir;
    const FlightRecord r = sample_record();
    const std::string path = dir / "flight.csv";
    write_flight_record(path, r);
    EXPECT_EQ(read_flight_record(path), r);
    // Only the record is in the folder: no temporary left behind.
    int files = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path)) ++files;
    EXPECT_EQ(files, 1);
    // Missing file and missing folder are one-line errors naming the path.
    EXPECT_THROW(read_flight_record(dir / "nope.csv"), Error);
    EXPECT_THROW(write_flight_record(dir / "no/such/dir/f.csv", r), Error);
    // A garbage file names the file.
    std::ofstream(dir / "bad.csv") << "hello\n";
    try {
        read_flight_record(dir / "bad.csv");
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_EQ(e.subject(), dir / "bad.csv");
    }
}
