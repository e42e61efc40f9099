// The one exception type that crosses pbrlab's boundaries: a message that already names the
// file (and line or field) it is about, ready to print.
#pragma once

#include <stdexcept>
#include <string>

namespace pbrlab {

struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace pbrlab
