// A higher layer including a lower one, and calling fork: both allowed here.
#include "low/own.h"
inline int child() {
    return fork();
}
