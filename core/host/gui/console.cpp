#include "console.h"

#include <iostream>
#include <sstream>

#include "lab.h"
#include "util/error.h"
#include "view_status.h"

extern char** environ;

namespace pbrlab {

namespace {

const char* const kWorkspaceNote =
    "\nIn the lab, commands that take --submission (check, render, stability, gallery, grade) "
    "work on the open workspace unless the line gives one: --submission DIR for another "
    "folder, --submission '' for the reference solutions.\n";

// A command that runs in the GUI's process and changes its state, as a panel does.
class LocalCommand : public Command {
public:
    LocalCommand(std::string name, std::string summary, const ConsoleTarget& target,
                 std::string& output)
        : Command(std::move(name), std::move(summary)), target_(target), output_(output) {}

protected:
    const Lab& lab() const { return *target_.lab; }
    GuiState& state() const { return *target_.state; }
    Requests& requests() const { return *target_.requests; }

    const ConsoleTarget& target_;
    std::string& output_;
};

// As clicking a step in the steps panel.
class StepCommand : public LocalCommand {
public:
    using LocalCommand::LocalCommand;
    void declare(CLI::App& cmd) override {
        cmd.add_option("step", id_, "Step id (see `list`)")->required();
    }
    int run(const GlobalOptions&) override {
        const auto& modules = lab().registry().modules();
        for (size_t i = 0; i < modules.size(); ++i)
            if (modules[i].desc->id == id_) requests().selectStep = int(i);
        if (requests().selectStep < 0) lab().registry().find(id_);  // throws, listing the ids
        return 0;
    }

private:
    std::string id_;
};

// As moving a parameter's widget; the syntax of --set.
class SetCommand : public LocalCommand {
public:
    using LocalCommand::LocalCommand;
    void declare(CLI::App& cmd) override {
        cmd.add_option("assignments", sets_, "Parameter name=value of the step shown, as --set")
            ->required();
    }
    int run(const GlobalOptions&) override {
        const ModuleDesc& m = lab().module(state());
        ParamValues values = state().params.at(m.id);
        for (const std::string& s : sets_) applyAssignment(m.params, values, s);
        state().params[m.id] = values;  // all or nothing: a bad one changes none
        requests().moved = true;
        return 0;
    }

private:
    std::vector<std::string> sets_;
};

// As the scene chooser: a scene, or a glTF model lit like the step's scene (or NAME).
class SceneCommand : public LocalCommand {
public:
    using LocalCommand::LocalCommand;
    void declare(CLI::App& cmd) override {
        cmd.add_option("scene", scene_, "Scene name in assets/scenes (default: the step's own)");
        cmd.add_option("--model", model_, "A glTF model (.glb/.gltf), lit like the scene");
    }
    int run(const GlobalOptions&) override {
        state().sceneName = scene_;
        state().model = model_.empty() ? std::filesystem::path() : canonicalFile(model_);
        requests().reloadScene = true;
        return 0;
    }

private:
    std::string scene_, model_;
};

// As the view chooser; the names of --view.
class ViewCommand : public LocalCommand {
public:
    using LocalCommand::LocalCommand;
    void declare(CLI::App& cmd) override {
        cmd.add_option("view", view_, "student|solution|reference|difference|split or a term")
            ->required();
    }
    int run(const GlobalOptions&) override {
        parseView(view_, lab().termViews(), state().view, state().term);
        requests().recompose = requests().viewChosen = true;
        return 0;
    }

private:
    std::string view_;
};

// What the view panel says: the compile error, what the picture is, the statistics.
class StatusCommand : public LocalCommand {
public:
    using LocalCommand::LocalCommand;
    void declare(CLI::App&) override {}
    int run(const GlobalOptions&) override {
        const std::string& id = lab().module(state()).id;
        output_ += "step " + id + ", badge: " + badgeText(lab().badges().of(id).status) + "\n" +
                   describe(viewStatus(lab(), state()));
        return 0;
    }
};

// As the screenshot button, to a file of one's choice.
class ScreenshotCommand : public LocalCommand {
public:
    using LocalCommand::LocalCommand;
    void declare(CLI::App& cmd) override {
        cmd.add_option("file", file_, "The PNG to write (default: pbrlab-screenshot.png)");
    }
    int run(const GlobalOptions&) override {
        requests().screenshot = true;
        requests().screenshotFile = file_;
        return 0;
    }

private:
    std::string file_;
};

// For scripts (--command): the lines after it wait, the window drawing meanwhile.
class WaitCommand : public LocalCommand {
public:
    using LocalCommand::LocalCommand;
    void declare(CLI::App& cmd) override {
        cmd.add_option("--file", wait.file,
                       "Also until this file exists (a script that edits files meanwhile)");
        cmd.add_option("--timeout", seconds_, "Give up after this many seconds (default 300)");
    }
    int run(const GlobalOptions&) override {
        wait.active = true;
        wait.since = std::chrono::steady_clock::now();
        wait.until = wait.since + std::chrono::milliseconds(int64_t(seconds_ * 1000));
        return 0;
    }
    Console::Wait wait;

private:
    double seconds_ = 300;
};

class HelpCommand : public LocalCommand {
public:
    using LocalCommand::LocalCommand;
    void declare(CLI::App& cmd) override {
        cmd.add_option("command", command_, "A command: its options");
    }
    int run(const GlobalOptions&) override {
        // As `pbrlab --help` and `pbrlab COMMAND --help` print it (App::help would show the
        // help of the command parsed: this one).
        output_ += command_.empty() ? app->get_formatter()->make_help(app, app->get_name(),
                                                                      CLI::AppFormatMode::Normal)
                                    : app->get_subcommand(command_)->help(app->get_name());
        output_ += kWorkspaceNote;
        if (target_.lab && !lab().submission().empty())
            output_ += "The workspace: " + lab().submission().string() + "\n";
        return 0;
    }
    const CLI::App* app = nullptr;

private:
    std::string command_;
};

class ClearCommand : public LocalCommand {
public:
    using LocalCommand::LocalCommand;
    void declare(CLI::App&) override {}
    int run(const GlobalOptions&) override { return 0; }  // Console::runLine clears
};

template <typename T>
T* addLocal(Commands& commands, const char* name, const char* summary, const ConsoleTarget& target,
            std::string& output) {
    auto command = std::make_unique<T>(name, summary, target, output);
    T* raw = command.get();
    commands.push_back(std::move(command));
    return raw;
}

}  // namespace

std::unique_ptr<CommandLine> consoleCommandLine(const ConsoleTarget& target, std::string& output) {
    Commands c = shellCommands();
    addLocal<StepCommand>(c, "step", "GUI: show this step", target, output);
    addLocal<SetCommand>(c, "set", "GUI: set the step's parameters (name=value, as --set)", target,
                         output);
    addLocal<SceneCommand>(c, "scene", "GUI: show this scene or --model (as the chooser)", target,
                           output);
    addLocal<ViewCommand>(c, "view", "GUI: show this view (as --view)", target, output);
    addLocal<StatusCommand>(c, "status",
                            "GUI: what the view says (compile error, picture, statistics)", target,
                            output);
    addLocal<ScreenshotCommand>(c, "screenshot", "GUI: save the window (as the button)", target,
                                output);
    addLocal<WaitCommand>(c, "wait",
                          "GUI: hold the next lines until the picture is evaluated and the "
                          "step's badge graded",
                          target, output);
    HelpCommand* help = addLocal<HelpCommand>(
        c, "help", "GUI: list the commands, or one command's options", target, output);
    addLocal<ClearCommand>(c, "clear", "GUI: clear the console", target, output);
    auto line = std::make_unique<CommandLine>(std::move(c));
    help->app = &line->app;
    return line;
}

namespace {

// Parses `words`; on a CLI11 error, returns what the shell would print (else empty).
std::string parseWords(CommandLine& line, const std::vector<std::string>& words) {
    try {
        line.parse(words);
        return {};
    } catch (const CLI::ParseError& e) {
        std::ostringstream out, err;
        line.app.exit(e, out, err);
        return out.str() + err.str();
    }
}

}  // namespace

ConsoleParse parseConsoleLine(const std::string& text) {
    ConsoleParse parsed;
    try {
        parsed.words = splitWords(text);
    } catch (const Error& e) {
        parsed.message = std::string("error: ") + e.what() + "\n";
        return parsed;
    }
    std::string output;
    auto line = consoleCommandLine({}, output);
    parsed.message = parseWords(*line, parsed.words);
    if (Command* c = line->chosen(); c && parsed.message.empty()) {
        parsed.command = c->name;
        parsed.local = dynamic_cast<LocalCommand*>(c) != nullptr;
        parsed.given = line->given();
    }
    return parsed;
}

std::vector<std::string> inWorkspace(const std::vector<std::string>& words,
                                     const std::filesystem::path& workspace) {
    if (workspace.empty()) return words;
    std::string output;
    auto line = consoleCommandLine({}, output);
    if (!parseWords(*line, words).empty()) return words;
    const Command* command = line->chosen();
    if (!command || command->name == "gui") return words;
    const CLI::App* sub = line->app.get_subcommand(command->name);
    const CLI::Option* submission = sub->get_option_no_throw("--submission");
    if (!submission || submission->count() > 0) return words;
    for (const char* other : {"--batch", "--merge"})
        if (const CLI::Option* o = sub->get_option_no_throw(other); o && o->count() > 0)
            return words;
    std::vector<std::string> with = words;
    with.insert(with.end(), {"--submission", workspace.string()});
    return with;
}

Console::Console(std::vector<std::string> globalArguments, bool echo)
    : globalArguments_(std::move(globalArguments)), echo_(echo) {}

Console::~Console() {
    child_.reset();  // before the text its output goes to
}

void Console::submit(const std::string& line) {
    queue_.push_back(line);
}

bool Console::idle() const {
    return queue_.empty() && !child_ && !wait_.active;
}

std::string Console::text() const {
    std::lock_guard lock(mutex_);
    return text_;
}

void Console::clear() {
    std::lock_guard lock(mutex_);
    text_.clear();
}

void Console::append(const std::string& text) {
    if (text.empty()) return;
    std::lock_guard lock(mutex_);
    text_ += text;
    if (echo_) std::cout << text << std::flush;
}

void Console::poll(const ConsoleTarget& target) {
    if (child_ && child_->finished()) child_.reset();
    // One line a frame: a local command's requests (a step chosen) are carried out by the
    // frame before the next line reads the state.
    if (!child_ && !waiting(target) && !queue_.empty()) {
        const std::string line = queue_.front();
        queue_.pop_front();
        runLine(line, target);
    }
}

// `wait`: until the file exists (when given), and the lab has nothing left to update.
bool Console::waiting(const ConsoleTarget& target) {
    if (!wait_.active) return false;
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - wait_.since).count();
    char took[64];
    std::snprintf(took, sizeof took, "%.1f s", seconds);
    if (now > wait_.until) {
        append(std::string("wait: gave up after ") + took + "\n");
    } else {
        std::error_code ec;
        if (!wait_.file.empty() && !std::filesystem::exists(wait_.file, ec)) return true;
        if (target.lab && !target.lab->settled(*target.state)) return true;
        append(std::string("(waited ") + took + ")\n");
    }
    wait_ = {};
    return false;
}

void Console::runLine(const std::string& text, const ConsoleTarget& target) {
    append("> " + text + "\n");
    std::vector<std::string> words;
    try {
        words = splitWords(text);
    } catch (const Error& e) {
        append(std::string("error: ") + e.what() + "\n");
        return;
    }
    if (words.empty()) return;
    std::string output;
    auto line = consoleCommandLine(target, output);
    const std::string parseError = parseWords(*line, words);
    if (!parseError.empty()) return append(parseError);
    Command* command = line->chosen();
    if (!command) return;
    if (command->name == "clear") return clear();
    if (command->name == "gui") return append("gui: this is the lab, open already\n");
    if (!dynamic_cast<LocalCommand*>(command)) {
        if (target.lab) {
            const std::vector<std::string> inside = inWorkspace(words, target.lab->submission());
            if (inside.size() != words.size())
                append("(on the workspace: --submission " + inside.back() + ")\n");
            words = inside;
        }
        return startChild(words);
    }
    try {
        command->run(line->global);
        if (auto* wait = dynamic_cast<WaitCommand*>(command)) wait_ = wait->wait;
    } catch (const std::exception& e) {
        output += std::string("error: ") + e.what() + "\n";
    }
    append(output);
}

// The command runs as `pbrlab ARGS` would on the shell (platform::startPbrlab), with the GUI's
// own global arguments.
void Console::startChild(const std::vector<std::string>& words) {
    std::vector<std::string> args = globalArguments_;
    args.insert(args.end(), words.begin(), words.end());
    child_ = platform::startPbrlab(args, [this](const std::string& text) { append(text); });
}

}  // namespace pbrlab
