// The `gui` command of the headless grader (the grader bundle's pbrlab): it says where the GUI
// is instead of failing to parse.
#include "table.h"
#include "util/error.h"

namespace pbrlab {

namespace {

class NoGuiCommand : public Command {
public:
    NoGuiCommand()
        : Command("gui", "Not in this headless grader: the GUI is pbrlab's desktop build") {}
    void declare(CLI::App& cmd) override { cmd.allow_extras(); }
    int run(const GlobalOptions&) override {
        throw Error(
            "this pbrlab is the headless grader of a grader bundle: it has no GUI (run "
            "`pbrlab gui` from pbrlab's desktop build)");
    }
};

}  // namespace

std::unique_ptr<Command> guiCommand() {
    return std::make_unique<NoGuiCommand>();
}

}  // namespace pbrlab
