#pragma once
// Checks on option values shared by every subcommand.
//
// Whole numbers are decimal: CLI11 converts integers with strtoll(..., 0),
// which reads `010` as octal 8 and `0x10` as 16 and clamps
// 99999999999999999999 to the largest long long without a word. Options
// holding integers take `->transform(decimal<T>())` instead: `010` is 10,
// and a value outside T, a sign on an unsigned T or any other character is
// rejected as "--option: ..." (main prints it as one line).
#include <CLI/CLI.hpp>

#include <charconv>
#include <initializer_list>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

namespace overflight::app {

template <class T>
CLI::Validator decimal() {
    static_assert(std::is_integral_v<T>);
    return CLI::Validator(
        [](std::string& text) -> std::string {
            T value{};
            const char* begin = text.data();
            const char* end = text.data() + text.size();
            const auto [ptr, ec] = std::from_chars(begin, end, value, 10);
            if (ec == std::errc::result_out_of_range)
                return "'" + text + "' is out of range (" + std::to_string(std::numeric_limits<T>::min()) + ".." +
                       std::to_string(std::numeric_limits<T>::max()) + ")";
            if (ec != std::errc() || ptr != end) return "'" + text + "' is not a whole decimal number";
            text = std::to_string(value); // without leading zeros, for CLI11's base-detecting conversion
            return {};
        },
        "");
}

// "a,b[,c]" -> values; throws Error(option, "'TEXT' is not FORM") unless
// exactly `count` finite numbers separated by commas.
std::vector<double> parse_list(const std::string& text, const std::string& option, int count, const char* form);

// Throws Error(name, "empty file name") for each of `names` (as given to
// add_option, e.g. "-o") that the command line gave with an empty value:
// `-o ''` would otherwise mean "no output" or a file called "".
void reject_empty_names(const CLI::App& cmd, std::initializer_list<const char*> names);

} // namespace overflight::app
