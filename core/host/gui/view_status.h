// What the view panel says in words around the picture: the student's compile error, what the
// picture is of, and the statistics against the CPU reference. The view panel draws it; the
// console's `status` prints it, so a scripted run can read what the window shows.
#pragma once

#include <string>
#include <utility>
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
    // The solution itself is outside the band on this GPU: why the rows cannot judge the
    // student's file here, and what does (the badge).
    std::string bandNote;
    // What the step's badge says beyond its word: its first sentence (what is wrong), and the
    // rest of the grader's message (the figures, the checks), shown folded.
    std::string grade, gradeDetails;
};

// A grader's message as its first sentence and the rest (empty when it is one sentence): a
// sentence ends at '.', '?' or '!' before a space and a capital letter ("3.142 x", ".. 0.2"
// and "(PI, 4) is off); integral" do not end one).
std::pair<std::string, std::string> firstSentence(const std::string& message);

ViewStatus viewStatus(const Lab& lab, const GuiState& state);

// As lines of text, the compile error's indented (the console's `status`).
std::string describe(const ViewStatus& status);

}  // namespace pbrlab
