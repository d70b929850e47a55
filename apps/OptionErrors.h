#pragma once
// The libraries report errors in their own terms ("triangle budget: 0 is
// below 2", "vehicle start: position ... is outside the terrain"); the
// command line names the option that set the value instead, so a user sees
// "--triangles: triangle budget 0 is below 2". One table for every command.
#include "core/Error.h"

namespace overflight::app {

// `e` with its subject replaced by the option that sets it, the old subject
// leading the problem; `e` itself when its subject is a file or already an option.
Error in_option_terms(const Error& e);

} // namespace overflight::app
