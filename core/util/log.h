// What the host did, made observable: counters for the work a scene may or may not need
// (program compiles, texture loads, precompute passes) and timed log lines. Tests assert on
// the counters; `--stats` and `--verbose` print them.
#pragma once

#include <string>

namespace pbrlab {

enum class Counter { ProgramCompiles, TextureLoads, PrecomputePasses, Count };

void countEvent(Counter counter);
int eventCount(Counter counter);
void resetCounters();
const char* counterName(Counter counter);

// Printed to stderr as "[category] message" when verbose logging is on; always kept in
// the in-memory journal that `--stats` prints.
void logLine(const std::string& category, const std::string& message);
void setVerbose(bool verbose);
const std::string& journal();

}  // namespace pbrlab
