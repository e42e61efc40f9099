// The commands' one vocabulary: the GUI's console parses a line into the same command with the
// same options as the shell does, and refuses a wrong one with the shell's message.
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "commands/command.h"
#include "commands/session.h"
#include "gui/console.h"
#include "util/error.h"

using namespace pbrlab;

namespace {

using Given = std::map<std::string, std::vector<std::string>>;

// The shell's parse of `pbrlab WORDS...`: the command chosen and its options.
std::pair<std::string, Given> shellParse(const std::vector<std::string>& words) {
    CommandLine line(shellCommands());
    line.parse(words);
    return {line.chosen() ? line.chosen()->name : "", line.given()};
}

// What the real executable prints for `pbrlab ARGS` (stdout and stderr).
std::string executableOutput(const std::string& args) {
    std::string out;
    FILE* p = popen((PBRLAB_EXECUTABLE " " + args + " 2>&1").c_str(), "r");
    char buffer[512];
    for (size_t n; (n = fread(buffer, 1, sizeof buffer, p)) > 0;) out.append(buffer, n);
    pclose(p);
    return out;
}

}  // namespace

TEST(Commands, TheConsoleParsesALineIntoTheShellsCommandWithTheSameOptions) {
    const std::string line =
        "render ndf --scene plane --set light_dir=0,1,0 --set x=1 --out 'my picture.png'";
    const ConsoleParse console = parseConsoleLine(line);
    ASSERT_EQ(console.message, "");
    EXPECT_EQ(console.command, "render");
    EXPECT_FALSE(console.local);
    const auto [name, given] =
        shellParse({"render", "ndf", "--scene", "plane", "--set", "light_dir=0,1,0", "--set", "x=1",
                    "--out", "my picture.png"});
    EXPECT_EQ(name, "render");
    EXPECT_EQ(console.given, given);
    // And what both read is what was written, not merely the same.
    EXPECT_EQ(given.at("--scene"), std::vector<std::string>{"plane"});
    EXPECT_EQ(given.at("--set"), (std::vector<std::string>{"light_dir=0,1,0", "x=1"}));
    EXPECT_EQ(given.at("--out"), std::vector<std::string>{"my picture.png"});
    EXPECT_EQ(given.at("step"), std::vector<std::string>{"ndf"});
}

TEST(Commands, EveryCommandThatTakesOneStepTakesItPositionally) {
    for (const char* command : {"render", "check", "gui", "new-step"}) {
        std::vector<std::string> words = {command, "ndf"};
        if (std::string(command) == "render" || std::string(command) == "new-step")
            words.insert(words.end(), {"--out", "x"});
        // CLI11 names an option by its long name when it has one (gui's alias, below).
        const std::string name = std::string(command) == "gui" ? "--module" : "step";
        EXPECT_EQ(shellParse(words).second.at(name), std::vector<std::string>{"ndf"}) << command;
    }
    // gui --module, the older spelling, is the same option.
    EXPECT_EQ(shellParse({"gui", "--module", "ndf"}).second, shellParse({"gui", "ndf"}).second);
    // grade takes its submission positionally or as --submission, like every other command.
    EXPECT_EQ(shellParse({"grade", "--submission", "kit"}).second,
              shellParse({"grade", "kit"}).second);
}

TEST(Commands, TheConsoleRefusesAWrongLineWithTheShellsMessage) {
    for (const std::string args : {"render ndf --bogus 1 --out x.png", "render --out x.png",
                                   "renderr ndf", "check ndf --size"}) {
        const ConsoleParse console = parseConsoleLine(args);
        EXPECT_EQ(console.command, "") << args;
        EXPECT_FALSE(console.message.empty()) << args;
        EXPECT_EQ(console.message, executableOutput(args)) << args;
    }
}

TEST(Commands, TheConsolesOwnCommandsAreListedWithTheShellsInHelp) {
    const ConsoleParse help = parseConsoleLine("help");
    EXPECT_EQ(help.command, "help");
    EXPECT_TRUE(help.local);
    for (const char* local : {"step", "set", "scene", "view"}) {
        const ConsoleParse p = parseConsoleLine(std::string(local) + " x=1");
        EXPECT_EQ(p.command, local) << p.message;
        EXPECT_TRUE(p.local) << local;
    }
    // `set` takes what --set takes, and needs one.
    EXPECT_EQ(parseConsoleLine("set light_dir=0,1,0 samples=3").given.at("assignments"),
              (std::vector<std::string>{"light_dir=0,1,0", "samples=3"}));
    EXPECT_NE(parseConsoleLine("set").message.find("assignments is required"), std::string::npos)
        << parseConsoleLine("set").message;
    // `--help` prints the shell's help text for a command.
    EXPECT_EQ(parseConsoleLine("render --help").message, executableOutput("render --help"));
}

// In the lab, `check ndf` grades the open workspace, as the badge does; a line that names a
// folder (or '' for the reference solutions) keeps it.
TEST(Commands, InTheLabCommandsThatTakeASubmissionWorkOnTheWorkspace) {
    using Words = std::vector<std::string>;
    const std::filesystem::path kit = "/home/student/kit";
    for (const Words& line : {Words{"check", "ndf"}, Words{"render", "ndf", "--out", "x.png"},
                              Words{"stability", "ndf"}, Words{"grade"}}) {
        Words expected = line;
        expected.insert(expected.end(), {"--submission", kit.string()});
        EXPECT_EQ(inWorkspace(line, kit), expected) << line[0];
    }
    for (const Words& line :
         {Words{"check", "ndf", "--submission", "other"}, Words{"check", "ndf", "--submission", ""},
          Words{"grade", "other"}, Words{"grade", "--batch", "class", "--out", "r"}, Words{"list"},
          Words{"mutants", "ndf"}, Words{"kit", "--out", "k"}, Words{"gui"},
          Words{"check", "--bogus"}})
        EXPECT_EQ(inWorkspace(line, kit), line) << line[0];
    // No workspace open: the reference solutions, as on the shell.
    EXPECT_EQ(inWorkspace({"check", "ndf"}, {}), (Words{"check", "ndf"}));
}

TEST(Commands, SplitsALineAsAShellDoesWithoutExpansions) {
    EXPECT_EQ(splitWords("  render  ndf\t--out \"a b.png\" --set 'x=1 2' c\\ d \"\" "),
              (std::vector<std::string>{"render", "ndf", "--out", "a b.png", "--set", "x=1 2",
                                        "c d", ""}));
    EXPECT_THROW(splitWords("render 'ndf"), Error);
}

TEST(Commands, ASizeIsWidthByHeightOrOneSideForASquare) {
    EXPECT_EQ(parseSize("640x480").width, 640);
    EXPECT_EQ(parseSize("640x480").height, 480);
    EXPECT_EQ(parseSize("96").width, 96);
    EXPECT_EQ(parseSize("96").height, 96);
    EXPECT_EQ(parseSquareSize("96x96"), 96);
    for (const char* bad : {"", "x", "5x", "0x5", "1", "9000", "64x64x", "64y64", "64x"})
        EXPECT_THROW(parseSize(bad), Error) << bad;
    EXPECT_THROW(parseSquareSize("96x64"), Error);
}
