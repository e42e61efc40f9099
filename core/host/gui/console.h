// The GUI's command line: the shell's commands (commands/), parsed with the same CLI11
// declarations and run as a child process of this executable with their output captured (on
// the open workspace: inWorkspace), and the GUI-local commands (step, set, scene, view,
// status, screenshot, wait, help, clear) that change GuiState as the panels do or report on
// it. Lines run one after another; the window keeps drawing meanwhile.
#pragma once

#include <array>
#include <chrono>
#include <deque>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "commands/command.h"
#include "platform.h"

namespace pbrlab {

class Lab;
struct GuiState;
struct Requests;

// What the GUI-local commands act on (null while only parsing).
struct ConsoleTarget {
    const Lab* lab = nullptr;
    GuiState* state = nullptr;
    Requests* requests = nullptr;
};

// A console line, parsed.
struct ConsoleParse {
    std::vector<std::string> words;  // as splitWords splits the line
    std::string command;             // the command chosen; empty when the line did not parse
    bool local = false;              // a GUI-local command, run in this process
    std::string message;             // why it did not parse (as the shell prints it), or help
    std::map<std::string, std::vector<std::string>> given;  // CommandLine::given()
};

// Every shell command and the GUI-local ones on one command line; `target` is what the local
// ones change when run.
// `output` receives what they print.
std::unique_ptr<CommandLine> consoleCommandLine(const ConsoleTarget& target, std::string& output);

// Parses one line with the console's command line (nothing runs).
ConsoleParse parseConsoleLine(const std::string& line);

// In the lab, a shell command that takes --submission (check, render, stability, gallery,
// grade) works on the open workspace: `words` with `--submission WORKSPACE` added when the
// line gives none (nor grade's --batch or --merge); else `words` as they are. An explicit
// --submission wins (--submission '' for the reference solutions).
std::vector<std::string> inWorkspace(const std::vector<std::string>& words,
                                     const std::filesystem::path& workspace);

class Console {
public:
    // `globalArguments`: the GUI's own --modules/--verbose, given to every child command.
    // `echo`: also print the console's output on stdout (scripted runs).
    Console(std::vector<std::string> globalArguments, bool echo);
    ~Console();  // stops a command still running

    // Queues a line; it runs when the ones before it have finished.
    void submit(const std::string& line);
    // Each frame: collects the running command's output and starts the next queued line.
    void poll(const ConsoleTarget& target);
    // No line queued or running.
    bool idle() const;
    // No line queued or running, `wait` aside (it only watches the lab).
    bool quiet() const { return queue_.empty() && !child_; }
    // The console's `wait` holds the lines after it until this is met.
    struct Wait {
        bool active = false;
        std::filesystem::path file;  // and this exists (empty: no file)
        std::chrono::steady_clock::time_point since, until;
    };
    bool running() const { return child_ != nullptr; }
    // Everything shown so far (the typed lines with "> ", then their output).
    std::string text() const;
    void clear();

    std::array<char, 512> input{};     // the input field's text
    std::vector<std::string> history;  // the lines typed, oldest first (up / down recall them)
    int historyIndex = -1;             // -1: not recalling
    size_t shownSize = 0;              // of text() when last drawn: more means scroll down

private:
    void append(const std::string& text);
    void runLine(const std::string& line, const ConsoleTarget& target);
    void startChild(const std::vector<std::string>& words);
    bool waiting(const ConsoleTarget& target);

    std::vector<std::string> globalArguments_;
    bool echo_ = false;
    std::deque<std::string> queue_;
    Wait wait_;
    mutable std::mutex mutex_;  // text_, written by the command's output thread
    std::string text_;
    std::unique_ptr<platform::PbrlabProcess> child_;  // the command running, if any
};

}  // namespace pbrlab
