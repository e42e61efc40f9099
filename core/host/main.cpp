// pbrlab: the command line. Each sub-command is an object (commands/); this parses the
// arguments with their declarations and runs the one chosen. The GUI's console parses with
// the same declarations (gui/panel_console.cpp), so both read the same vocabulary.
#include "commands/command.h"
#include "native/huge_pages.h"

int main(int argc, char** argv) {
    pbrlab::restartWithHugePages(argc, argv);
    pbrlab::CommandLine commandLine(pbrlab::shellCommands());
    try {
        commandLine.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return commandLine.app.exit(e);
    }
    return commandLine.run();
}
