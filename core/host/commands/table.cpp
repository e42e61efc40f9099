// The table of commands, and the command line that parses and runs them.
#include "table.h"

#include <algorithm>
#include <iostream>

#include "util/error.h"
#include "util/log.h"

namespace pbrlab {

Commands shellCommands() {
    Commands c;
#ifdef __EMSCRIPTEN__
    return c;  // a page starts no processes: its console has the GUI's own commands only
#endif
    c.push_back(listCommand());
    c.push_back(renderCommand());
    c.push_back(checkCommand());
    c.push_back(guiCommand());
    c.push_back(permutationsCommand());
    c.push_back(modelsCommand());
    c.push_back(environmentCommand());
    c.push_back(gradeCommand());
    c.push_back(classroomCommand());
    c.push_back(convergeCommand());
    c.push_back(kitCommand());
    c.push_back(autograderCommand());
    c.push_back(newStepCommand());
    c.push_back(precomputeCommand());
    c.push_back(stabilityCommand());
    c.push_back(texturesCommand());
    c.push_back(mutantsCommand());
    c.push_back(galleryCommand());
    return c;
}

CommandLine::CommandLine(Commands commands)
    : app("pbrlab: a step-by-step lab for physically based rendering", "pbrlab"),
      commands_(std::move(commands)) {
    app.require_subcommand(1);
    app.add_option("--modules", global.modulesDirs,
                   "A folder of step libraries (pbrlab-<id>.so) and step folders, loaded after the "
                   "built-in steps and $PBRLAB_MODULES (colon-separated); repeatable");
    app.add_flag("--verbose,-v", global.verbose,
                 "Log compiles, texture loads and passes to stderr");
    for (const auto& c : commands_) c->declare(*app.add_subcommand(c->name, c->summary));
}

void CommandLine::parse(std::vector<std::string> words) {
    std::reverse(words.begin(), words.end());  // CLI11 takes them last first
    app.parse(words);
}

Command* CommandLine::chosen() const {
    for (const auto& c : commands_)
        if (app.got_subcommand(c->name)) return c.get();
    return nullptr;
}

std::map<std::string, std::vector<std::string>> CommandLine::given() const {
    std::map<std::string, std::vector<std::string>> options;
    if (const Command* command = chosen())
        for (const CLI::Option* o : app.get_subcommand(command->name)->get_options())
            if (o->count() > 0) options[o->get_name()] = o->results();
    return options;
}

int CommandLine::run() {
    setVerbose(global.verbose);
    Command* command = chosen();
    if (!command) return 0;
    try {
        return command->run(global);
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    }
}

std::vector<std::string> splitWords(const std::string& line) {
    std::vector<std::string> words;
    std::string word;
    bool inWord = false;
    char quote = 0;
    for (size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quote) {
            if (c == quote)
                quote = 0;
            else if (c == '\\' && quote == '"' && i + 1 < line.size())
                word += line[++i];
            else
                word += c;
        } else if (c == '\'' || c == '"') {
            quote = c;
            inWord = true;
        } else if (c == '\\' && i + 1 < line.size()) {
            word += line[++i];
            inWord = true;
        } else if (c == ' ' || c == '\t' || c == '\n') {
            if (inWord) words.push_back(word);
            word.clear();
            inWord = false;
        } else {
            word += c;
            inWord = true;
        }
    }
    if (quote) throw Error(std::string("unterminated ") + quote + " quote in: " + line);
    if (inWord) words.push_back(word);
    return words;
}

}  // namespace pbrlab
