#include "util/log.h"

#include <array>
#include <atomic>
#include <iostream>
#include <mutex>

namespace pbrlab {
namespace {
// Counted and logged from more than one thread (the GUI's evaluation thread beside its window).
std::array<std::atomic<int>, size_t(Counter::Count)> counters{};
std::atomic<bool> verboseLogging{false};
std::mutex journalMutex;  // journalText and the lines on stderr
std::string journalText;
}  // namespace

void countEvent(Counter counter) {
    ++counters[size_t(counter)];
}
int eventCount(Counter counter) {
    return counters[size_t(counter)];
}
void resetCounters() {
    for (std::atomic<int>& c : counters) c = 0;
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
    std::lock_guard<std::mutex> lock(journalMutex);
    journalText += line;
    if (verboseLogging) std::cerr << line;
}
void setVerbose(bool verbose) {
    verboseLogging = verbose;
}
// A copy per thread, taken under the lock (the reference stays valid until this thread's next
// call): the GUI's window reads it while its evaluation thread logs.
const std::string& journal() {
    thread_local std::string copy;
    std::lock_guard<std::mutex> lock(journalMutex);
    copy = journalText;
    return copy;
}

}  // namespace pbrlab
