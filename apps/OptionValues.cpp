#include "OptionValues.h"

#include "core/Error.h"

namespace overflight::app {

void reject_empty_names(const CLI::App& cmd, std::initializer_list<const char*> names) {
    for (const char* name : names) {
        const CLI::Option* option = cmd.get_option(name);
        for (const std::string& value : option->results())
            if (value.empty()) throw Error(name, "the file name is empty");
    }
}

} // namespace overflight::app
