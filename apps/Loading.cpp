#include "Loading.h"

#include <exception>
#include <utility>

namespace overflight::app {

namespace {

std::string& current() {
    static std::string what;
    return what;
}

} // namespace

LoadingScope::LoadingScope(std::string what)
    : previous_(std::exchange(current(), std::move(what))), exceptions_(std::uncaught_exceptions()) {}

LoadingScope::~LoadingScope() {
    if (std::uncaught_exceptions() == exceptions_) current() = std::move(previous_);
}

const std::string& being_loaded() { return current(); }

} // namespace overflight::app
