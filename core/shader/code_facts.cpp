#include "shader/code_facts.h"

#include <cctype>
#include <regex>

namespace pbrlab {

namespace {

// The code without its comments (a commented-out `while (true)` is no loop).
std::string withoutComments(const std::string& code) {
    std::string out;
    for (size_t i = 0; i < code.size(); ++i) {
        if (code.compare(i, 2, "//") == 0) {
            i = code.find('\n', i);
            if (i == std::string::npos) break;
            out += '\n';
        } else if (code.compare(i, 2, "/*") == 0) {
            i = code.find("*/", i + 2);
            if (i == std::string::npos) break;
            ++i;
            out += ' ';
        } else {
            out += code[i];
        }
    }
    return out;
}

}  // namespace

std::string whyAlwaysZero(const std::string& code) {
    const std::string text = withoutComments(code);
    // A loop whose condition is always true: while (true), while (1), for (...; ; ...),
    // for (...; true; ...), do { } while (true).
    static const std::regex endless(
        R"((\bwhile\s*\(\s*(true|1)\s*\))|(\bfor\s*\([^;()]*;\s*(true|1)?\s*;[^)]*\)))");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), endless);
         it != std::sregex_iterator(); ++it) {
        // Its body: the braces that follow (the statement up to ';' without them). A
        // do-while's body is before it, and its while is followed by ';'.
        size_t at = size_t(it->position() + it->length());
        while (at < text.size() && std::isspace(static_cast<unsigned char>(text[at]))) ++at;
        std::string body;
        if (at < text.size() && text[at] == ';') {
            const size_t close = text.rfind('}', size_t(it->position()));
            int depth = 0;
            size_t open = close;
            for (size_t i = close + 1; i-- > 0;) {
                depth += text[i] == '}' ? 1 : text[i] == '{' ? -1 : 0;
                if (depth == 0) {
                    open = i;
                    break;
                }
            }
            if (close != std::string::npos) body = text.substr(open, close - open + 1);
        } else if (at < text.size() && text[at] == '{') {
            int depth = 0;
            size_t end = at;
            for (; end < text.size(); ++end) {
                depth += text[end] == '{' ? 1 : text[end] == '}' ? -1 : 0;
                if (depth == 0) break;
            }
            body = text.substr(at, end - at + 1);
        } else {
            body = text.substr(at, text.find(';', at) - at);
        }
        static const std::regex exit(R"(\b(break|return|discard)\b)");
        if (!std::regex_search(body, exit))
            return "Your function has a loop that never ends (`" + it->str() +
                   "` with no break or return): the GLSL compiler deletes a loop with no way "
                   "out, and the function then returns an undefined value (0 here). Give the "
                   "loop a condition that ends it.";
    }
    if (code.find("TODO: implement") != std::string::npos) return "Is it still the kit's stub?";
    return "";
}

}  // namespace pbrlab
