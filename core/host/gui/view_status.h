// What the view panel says in words around the picture: the student's compile error, what the
// picture is of, and the statistics against the CPU reference. The view panel draws it; the
// console's `status` prints it, so a scripted run can read what the window shows.
#pragma once

#include <string>
#include <vector>

namespace pbrlab {

class Lab;
struct GuiState;

struct ViewStatus {
    // The student's file does not compile (or may not be read): what that means for the
    // picture, then the compiler's text with file:line. Empty: it compiles.
    std::string error, errorLog;
    bool lastGood = false;  // the picture and statistics are the last good program's
    std::string notice;     // the picture is the solution's, and why
    std::string statsHeading;
    struct Row {
        std::string text;
        bool ok = false;
    };
    std::vector<Row> rows;  // the student's (or the last good program's), then the solution's
    std::string grade;      // what the step's badge says beyond its word
};

ViewStatus viewStatus(const Lab& lab, const GuiState& state);

// As lines of text, the compile error's indented (the console's `status`).
std::string describe(const ViewStatus& status);

}  // namespace pbrlab
