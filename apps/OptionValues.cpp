#include "OptionValues.h"

#include "core/Error.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace overflight::app {

std::vector<double> parse_list(const std::string& text, const std::string& option, int count, const char* form) {
    std::vector<double> v;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        try {
            std::size_t used = 0;
            const double x = std::stod(item, &used);
            if (used != item.size() || !std::isfinite(x)) throw std::invalid_argument(item);
            v.push_back(x);
        } catch (const std::exception&) {
            throw Error(option, "'" + text + "' is not " + form);
        }
    }
    if (int(v.size()) != count) throw Error(option, "'" + text + "' is not " + form);
    return v;
}

void reject_empty_names(const CLI::App& cmd, std::initializer_list<const char*> names) {
    for (const char* name : names) {
        const CLI::Option* option = cmd.get_option(name);
        for (const std::string& value : option->results())
            if (value.empty()) throw Error(name, "the file name is empty");
    }
}

} // namespace overflight::app
