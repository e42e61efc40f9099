// The steps linked into the program (pbrlab/module.h's PBRLAB_STATIC_STEP): the browser's build
// registers every step this way; the desktop loads libraries and registers none.
#include "pbrlab/module.h"

namespace pbrlab {

namespace {

std::vector<StaticModule>& registered() {
    static std::vector<StaticModule> modules;  // filled before main(), by each step's object
    return modules;
}

}  // namespace

bool registerStaticModule(StaticModule module) {
    registered().push_back(module);
    return true;
}

const std::vector<StaticModule>& staticModules() {
    return registered();
}

}  // namespace pbrlab
