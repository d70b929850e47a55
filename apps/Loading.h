#pragma once
// What the command is reading right now, so that running out of memory, the
// one failure no loader can always turn into its own Error (a process limit
// such as `ulimit -v` is not known in advance), is still reported by main as
// one line naming the file rather than as a bare exception name.
#include <string>

namespace overflight::app {

// Marks `what` (a path or option) as being loaded for the scope's lifetime.
// Left by an exception, the mark stays, so that main's handler still sees
// what was being loaded when the exception began.
class LoadingScope {
public:
    explicit LoadingScope(std::string what);
    ~LoadingScope();
    LoadingScope(const LoadingScope&) = delete;
    LoadingScope& operator=(const LoadingScope&) = delete;

private:
    std::string previous_;
    int exceptions_ = 0; // std::uncaught_exceptions() on entry
};

// The innermost `what` being loaded, or an empty string.
const std::string& being_loaded();

} // namespace overflight::app
