#include "pbrlab/log.h"

#include <array>
#include <iostream>

namespace pbrlab {
namespace {
std::array<int, size_t(Counter::Count)> counters{};
bool verboseLogging = false;
std::string journalText;
}  // namespace

void countEvent(Counter counter) {
    ++counters[size_t(counter)];
}
int eventCount(Counter counter) {
    return counters[size_t(counter)];
}
void resetCounters() {
    counters.fill(0);
}
const char* counterName(Counter counter) {
    switch (counter) {
        case Counter::ProgramCompiles:
            return "programs compiled";
        case Counter::TextureLoads:
            return "textures loaded";
        case Counter::PrecomputePasses:
            return "precompute passes";
        default:
            return "?";
    }
}

void logLine(const std::string& category, const std::string& message) {
    std::string line = "[" + category + "] " + message + "\n";
    journalText += line;
    if (verboseLogging) std::cerr << line;
}
void setVerbose(bool verbose) {
    verboseLogging = verbose;
}
const std::string& journal() {
    return journalText;
}

}  // namespace pbrlab
