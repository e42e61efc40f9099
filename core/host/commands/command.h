// pbrlab's sub-commands as objects: each declares its options on a CLI11 sub-command and runs
// with them. The shell (main.cpp) and the GUI's console (gui/panel_console.cpp) parse with
// the same declarations, so a command reads and fails the same way in both.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace pbrlab {

// The options before the sub-command (`pbrlab --modules DIR -v render ...`).
struct GlobalOptions {
    std::vector<std::string> modulesDirs;  // --modules, after the built-in and $PBRLAB_MODULES
    bool verbose = false;
};

// One sub-command. declare() binds its options to the object's own fields; run() reads them
// once CLI11 has parsed the line.
class Command {
public:
    Command(std::string name, std::string summary)
        : name(std::move(name)), summary(std::move(summary)) {}
    virtual ~Command() = default;
    virtual void declare(CLI::App& cmd) = 0;
    // The exit status; pbrlab::Error and other exceptions are reported by CommandLine::run.
    virtual int run(const GlobalOptions& global) = 0;

    const std::string name, summary;
};

using Commands = std::vector<std::unique_ptr<Command>>;

// Every shell command, in `pbrlab --help` order (commands/table.cpp).
Commands shellCommands();

// One CLI11 app holding the global options and the given commands (each declared once).
class CommandLine {
public:
    explicit CommandLine(Commands commands);

    // Parses; throws CLI::ParseError (CLI::App::exit prints it as the shell does).
    void parse(int argc, char** argv) { app.parse(argc, argv); }
    void parse(std::vector<std::string> words);  // without the program name
    // The command the last parse chose (nullptr: none).
    Command* chosen() const;
    // The options given to it, by name, with the words given (what the tests compare).
    std::map<std::string, std::vector<std::string>> given() const;
    // Runs the chosen command; an exception becomes "error: ..." on stderr and exit status 2.
    int run();

    CLI::App app;
    GlobalOptions global;

private:
    Commands commands_;
};

// A line split into words as a POSIX shell splits it without expansions: blanks separate,
// '...' and "..." quote, a backslash escapes the next character. Throws pbrlab::Error on an
// unterminated quote.
std::vector<std::string> splitWords(const std::string& line);

}  // namespace pbrlab
