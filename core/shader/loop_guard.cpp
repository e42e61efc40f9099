#include "shader/loop_guard.h"

#include <algorithm>
#include <cctype>
#include <climits>
#include <regex>

#include "shader/preprocess.h"

namespace pbrlab {

int loopBudget(const LoopLimits& limits) {
    // A function's own loops over nothing the host gives (a colour's channels, a short series,
    // a small table): 2^12, many times what any step needs.
    constexpr double kOwn = 4096;
    // Per light slot: the loop over the lights, and up to 63 iterations per light in what it
    // calls (a BRDF with a loop of its own). Every program gets it: a step's function may read
    // the light arrays, and 64 x 64 is as much again as kOwn.
    constexpr double kPerLight = 64;
    // Per texel of uEnvironment's mip 0 (6 side^2): a sum over every texel with its row loops,
    // or a Riemann sum in angles up to twice as fine as the texels.
    constexpr double kPerTexel = 2;
    // Per unit of a count: the loop over the samples and, per sample, what the functions it
    // calls loop (a radical inverse bit by bit is 32 iterations, two such sequences 64): twice
    // that.
    constexpr double kPerCount = 128;
    // What the native renderer runs: llvmpipe ends the loops of an invocation after 65535
    // iterations in all (LP_MAX_TGSI_LOOP_ITERATIONS, one counter for every loop of the
    // shader, the host's too), silently. The guard ends a runaway loop before that, so that a
    // file's verdict is the guard's on the desktop as in the page; a function that needs more
    // was never computed whole natively, and is now cut with its loop named. kHostLoops leaves
    // room for the host's loops beside the student's (the discrepancy view's 1024 points, 64
    // lights, the diagnosis build's own).
    constexpr double kNativeLoops = 65535, kHostLoops = 4096;
    double budget = kOwn + kPerLight * double(limits.lightSlots) +
                    kPerTexel * 6.0 * double(limits.environmentSize) * limits.environmentSize;
    double product = 1;
    for (double c : limits.counts) product *= std::max(c, 1.0);
    // Loops over two counts may nest: their product.
    if (!limits.counts.empty()) budget += kPerCount * product;
    budget = std::min(budget, kNativeLoops - kHostLoops);
    // A loop over a count beyond that still runs whole (65536 samples, the largest the host
    // allows): llvmpipe drops its last iteration (one sample of 65536, inside every band), the
    // page runs it all.
    if (!limits.counts.empty()) budget = std::max(budget, kOwn + product);
    return int(std::min(budget, double(INT_MAX / 2)));
}

namespace {

[[noreturn]] void refuse(const std::string& name, int line, const std::string& why) {
    throw ShaderError(name + ":" + std::to_string(line) + ": error: " + why);
}

bool wordChar(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

// The file as the compiler reads its code: line continuations joined (`origin`: each
// character's offset in the file, `lineOf`: its line), comments replaced by spaces.
struct Code {
    std::string text;
    std::vector<size_t> origin;
    std::vector<int> lineOf;
};

Code codeOf(const std::string& file) {
    Code c;
    for (size_t i = 0, line = 1; i < file.size(); ++i) {
        if (file[i] == '\\' &&
            (file.compare(i + 1, 1, "\n") == 0 || file.compare(i + 1, 2, "\r\n") == 0)) {
            i += file[i + 1] == '\r' ? 2 : 1;
            ++line;
            continue;
        }
        c.text += file[i];
        c.origin.push_back(i);
        c.lineOf.push_back(int(line));
        if (file[i] == '\n') ++line;
    }
    bool block = false, lineComment = false;
    for (size_t i = 0; i < c.text.size(); ++i) {
        char& ch = c.text[i];
        const char next = i + 1 < c.text.size() ? c.text[i + 1] : '\0';
        if (ch == '\n') {
            lineComment = false;
        } else if (lineComment) {
            ch = ' ';
        } else if (block) {
            if (ch == '*' && next == '/') {
                block = false;
                c.text[i + 1] = ' ';
            }
            ch = ' ';
        } else if (ch == '/' && (next == '/' || next == '*')) {
            (next == '/' ? lineComment : block) = true;
            ch = ' ';
        }
    }
    return c;
}

struct Insertion {
    size_t at;  // offset in the file
    std::string text;
};

// A condition that declares a variable (`bool b = f()`): it cannot be passed to pbrlab_loop.
bool declares(const std::string& condition) {
    static const std::regex declaration(R"(^\s*(\w+\s+)+\w+\s*(\[[^\]]*\]\s*)?=([^=]|$))");
    return std::regex_search(condition, declaration);
}

// The ranges guardLoops scans: the code outside directives as one (`skip` marks the
// directives' characters), and each #define's body as its own (a loop in a macro is wrapped
// where it is written; its parentheses close there).
struct ScanRanges {
    std::vector<bool> skip;
    std::vector<std::pair<size_t, size_t>> defines;
};

// The file's directives found (a #define of a loop keyword refused).
ScanRanges scanRanges(const Code& code, const std::string& name) {
    const std::string& s = code.text;
    ScanRanges ranges{std::vector<bool>(s.size(), false), {}};
    for (size_t begin = 0; begin < s.size();) {
        size_t end = s.find('\n', begin);
        if (end == std::string::npos) end = s.size();
        const size_t first = s.find_first_not_of(" \t\r\f\v", begin);
        if (first < end && s[first] == '#') {
            std::fill(ranges.skip.begin() + long(begin), ranges.skip.begin() + long(end), true);
            static const std::regex define(R"(^#\s*define\s+(\w+))");
            std::smatch m;
            const std::string directive = s.substr(first, end - first);
            if (std::regex_search(directive, m, define)) {
                const std::string macro = m[1].str();
                if (macro == "for" || macro == "while" || macro == "do")
                    refuse(name, code.lineOf[first],
                           "#define " + macro +
                               ": a step's file may not redefine a loop keyword (pbrlab bounds "
                               "every loop of your file by its keywords)");
                size_t body = first + size_t(m.length(0));
                if (body < end && s[body] == '(') body = s.find(')', body) + 1;  // parameters
                if (body > first && body < end) ranges.defines.emplace_back(body, end);
            }
        }
        begin = end + 1;
    }
    return ranges;
}

// guardLoops' scan: each `for` and `while` of a range found, its site noted and its condition
// wrapped in pbrlab_loop (insertions into the file). `useSkip`: the range is the code outside
// directives (false: a #define's body).
struct LoopScan {
    const Code& code;
    const std::vector<bool>& skip;
    const std::string& name;  // the file as messages name it
    const std::string& file;  // the file as LoopSite names it
    std::vector<LoopSite>& sites;
    std::vector<Insertion>& insertions;

    // The code's character at i, a space in a directive when skipped.
    char codeAt(size_t i, bool useSkip) const { return useSkip && skip[i] ? ' ' : code.text[i]; }
    void scan(size_t begin, size_t end, bool useSkip);
    size_t guardLoop(const std::string& word, size_t keyword, size_t end, bool useSkip);
    size_t closingParenthesis(size_t open, size_t end, bool useSkip,
                              std::vector<size_t>& semicolons) const;
};

// Finds the loop keywords of [begin, end), guarding each loop.
void LoopScan::scan(size_t begin, size_t end, bool useSkip) {
    const std::string& s = code.text;
    for (size_t i = begin; i < end;) {
        if (!wordChar(codeAt(i, useSkip))) {
            ++i;
            continue;
        }
        size_t wordEnd = i;
        while (wordEnd < end && wordChar(codeAt(wordEnd, useSkip))) ++wordEnd;
        // A number's suffix (1e5, 2u) is no word; a field (.x) is no keyword.
        const bool isNumber = std::isdigit(static_cast<unsigned char>(s[i]));
        const bool isField = i > begin && codeAt(i - 1, useSkip) == '.';
        const std::string word = s.substr(i, wordEnd - i);
        const size_t keyword = i;
        i = wordEnd;
        if (isNumber || isField || (word != "while" && word != "for")) continue;
        i = guardLoop(word, keyword, end, useSkip);
    }
}

// Notes the loop whose keyword `word` is at `keyword` and wraps its condition; returns where
// the scan goes on.
size_t LoopScan::guardLoop(const std::string& word, size_t keyword, size_t end, bool useSkip) {
    const size_t wordEnd = keyword + word.size();
    const int line = code.lineOf[keyword];
    size_t open = wordEnd;
    while (open < end && std::isspace(static_cast<unsigned char>(codeAt(open, useSkip)))) ++open;
    if (open >= end || codeAt(open, useSkip) != '(')
        refuse(name, line,
               "`" + word +
                   "` without its parenthesis here: pbrlab bounds every loop of your "
                   "file, and needs the loop's condition written in parentheses right "
                   "after `" +
                   word + "` (not through a macro)");
    std::vector<size_t> semicolons;
    const size_t close = closingParenthesis(open, end, useSkip, semicolons);
    if (close == std::string::npos)
        refuse(name, line,
               "the parenthesis after `" + word + "` is not closed" +
                   (useSkip ? std::string() : " on the #define's line"));
    size_t from = open + 1, to = close;
    if (word == "for") {
        // Not three clauses: the compiler says what is wrong.
        if (semicolons.size() != 2) return wordEnd;
        from = semicolons[0] + 1;
        to = semicolons[1];
    }
    std::string condition;
    for (size_t j = from; j < to; ++j) condition += codeAt(j, useSkip);
    if (declares(condition))
        refuse(name, line,
               "a declaration as the loop's condition (`" + word +
                   " (... bool b = ...)`): declare the variable before the loop and "
                   "test it in the condition");
    const std::string k = std::to_string(sites.size() + 1);
    sites.push_back({file, line});
    if (condition.find_first_not_of(" \t\r\n\f\v") == std::string::npos) {
        if (word == "while") return wordEnd;  // `while ()`: the compiler's error
        insertions.push_back({code.origin[from - 1] + 1, " pbrlab_loop(" + k + ", true)"});
    } else {
        insertions.push_back({code.origin[from - 1] + 1, "pbrlab_loop(" + k + ", ("});
        insertions.push_back({code.origin[to], "))"});
    }
    // Nested loops in a for's clauses are no GLSL: what follows the parenthesis is next.
    return open + 1;
}

// The parenthesis that closes the one at `open` (npos: none before `end`), with the
// semicolons directly inside it (a for's clauses).
size_t LoopScan::closingParenthesis(size_t open, size_t end, bool useSkip,
                                    std::vector<size_t>& semicolons) const {
    int depth = 0;
    for (size_t j = open; j < end; ++j) {
        const char c = codeAt(j, useSkip);
        if (c == '(') ++depth;
        if (c == ')' && --depth == 0) return j;
        if (c == ';' && depth == 1) semicolons.push_back(j);
    }
    return std::string::npos;
}

}  // namespace

std::string guardLoops(const std::string& text, const std::string& name, const std::string& file,
                       std::vector<LoopSite>& sites) {
    const Code code = codeOf(text);
    const ScanRanges ranges = scanRanges(code, name);
    std::vector<Insertion> insertions;
    LoopScan loops{code, ranges.skip, name, file, sites, insertions};
    loops.scan(0, code.text.size(), true);
    for (const auto& [begin, end] : ranges.defines) loops.scan(begin, end, false);
    std::sort(insertions.begin(), insertions.end(),
              [](const Insertion& a, const Insertion& b) { return a.at > b.at; });
    std::string out = text;
    for (const Insertion& in : insertions) out.insert(in.at, in.text);
    return out;
}

std::string loopGuardPrelude(bool diagnosis) {
    std::string out = std::string("#define ") + kLoopGuardMacro + " 1\n" + "uniform int " +
                      kLoopBudgetUniform + R"(;
int pbrlab_loopsRun = 0;
bool pbrlab_loopCut = false;
)";
    if (diagnosis)
        return out + "int pbrlab_loopCutSite = 0;\nbool pbrlab_loop(int site, bool go);\n";
    return out + R"(bool pbrlab_loop(int site, bool go) {
    if (!go) return false;
    if (pbrlab_loopsRun >= pbrlab_loopBudget) {
        pbrlab_loopCut = true;
        return false;
    }
    ++pbrlab_loopsRun;
    return true;
}
)";
}

std::string loopGuardDiagnosis(size_t sites) {
    // The loops running, outermost first, each with the iterations of its current run: a loop
    // tested again pops the loops inside it (they ended), one whose condition is false pops
    // itself. A loop left by break or return stays until the loop around it iterates. No loop
    // here but at the cut: llvmpipe's iterations are counted for the whole shader (loopBudget),
    // so where a loop is on the stack is kept per site (pbrlab_loopAt: its index + 1, checked
    // against the stack, so a stale or unset entry reads as absent).
    const std::string n = std::to_string(std::max<size_t>(sites, 1));
    return "int pbrlab_loopStack[" + n + "];\nint pbrlab_loopRuns[" + n + "];\nint pbrlab_loopAt[" +
           n + " + 1];\n" + R"(int pbrlab_loopDepth = 0;
bool pbrlab_loop(int site, bool go) {
    int d = pbrlab_loopAt[site] - 1;
    if (d < 0 || d >= pbrlab_loopDepth || pbrlab_loopStack[d] != site) d = -1;
    if (!go) {
        if (d >= 0) pbrlab_loopDepth = d;
        return false;
    }
    if (pbrlab_loopsRun >= pbrlab_loopBudget) {
        if (!pbrlab_loopCut) {
            pbrlab_loopCutSite = site;
            int most = 0;
            for (int k = 0; k < pbrlab_loopDepth; ++k)
                if (pbrlab_loopRuns[k] > most) {
                    most = pbrlab_loopRuns[k];
                    pbrlab_loopCutSite = pbrlab_loopStack[k];
                }
        }
        pbrlab_loopCut = true;
        return false;
    }
    ++pbrlab_loopsRun;
    if (d < 0) {
        d = pbrlab_loopDepth;
        pbrlab_loopStack[d] = site;
        pbrlab_loopRuns[d] = 0;
        pbrlab_loopAt[site] = d + 1;
    }
    pbrlab_loopDepth = d + 1;
    ++pbrlab_loopRuns[d];
    return true;
}
)";
}

const std::vector<std::string>& loopGuardNames() {
    static const std::vector<std::string> names = {
        "pbrlab_loop",        "pbrlab_loopBudget", "pbrlab_loopsRun", "pbrlab_loopCut",
        "pbrlab_loopCutSite", "pbrlab_loopStack",  "pbrlab_loopRuns", "pbrlab_loopDepth"};
    return names;
}

}  // namespace pbrlab
