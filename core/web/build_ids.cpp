// util/digest.h's buildIds in the browser: none. The disk cache keys its files by the build IDs
// of the code that computed them; a page has no disk to keep them on, so nothing is cached.
#include "util/digest.h"

namespace pbrlab {

std::string buildIds(const std::vector<std::string>&) {
    return {};
}

}  // namespace pbrlab
