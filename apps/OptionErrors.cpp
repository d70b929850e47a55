#include "OptionErrors.h"

#include <string_view>
#include <utility>

namespace overflight::app {

Error in_option_terms(const Error& e) {
    static const std::pair<std::string_view, const char*> options[] = {
        {"triangle budget", "--triangles"}, {"screen-space error", "--error"}, {"tile cache", "--cache-mib"},
        {"near step", "--near-step"},       {"distance LOD", "--lod"},         {"tile size", "--tile-size"},
        {"key press", "--press"},           {"projection", "--projection"},    {"terrain method", "--method"},
        {"vehicle start", "--at"},          {"vehicle heading", "--heading"},
        {"memory bound", "--memory-mib"},
    };
    for (const auto& [subject, option] : options)
        if (e.subject() == subject) return Error(option, e.subject() + " " + e.problem());
    return e;
}

} // namespace overflight::app
