// A lower layer that includes a higher one and uses the native platform.
#include <sys/wait.h>

#include "high/fine.h"
#include "low/own.h"

int run() {
    return fork();
}
