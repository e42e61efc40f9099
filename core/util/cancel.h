// Stopping a long computation early when its result is no longer wanted: the GUI's
// evaluation thread asks between points of a CPU reference whether a newer edit superseded
// its job (seconds of work at high sample counts: brdf_lut's band at 1024 samples, 7-9 s on
// 2 cores), instead of finishing it for nothing.
#pragma once

#include <exception>
#include <functional>

namespace pbrlab {

// Whether the caller no longer wants the result; called from any thread, often (once per
// point). Empty: never.
using StopRequested = std::function<bool()>;

// Thrown by a computation that stopped because StopRequested said so: not an error, and never
// shown (the newer request's result is).
class Cancelled : public std::exception {
public:
    const char* what() const noexcept override { return "stopped: a newer request superseded it"; }
};

}  // namespace pbrlab
