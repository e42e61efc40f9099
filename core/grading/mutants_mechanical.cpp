#include "grading/mutants_mechanical.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <set>
#include <sstream>

namespace pbrlab {

namespace {

using Token = GlslToken;

bool isIdentStart(char c) {
    return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool isIdentChar(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

}  // namespace

std::vector<GlslToken> tokenizeGlsl(const std::string& s) {
    std::vector<Token> out;
    size_t i = 0;
    int line = 1;
    bool lineStart = true;
    auto push = [&](Token::Kind k, size_t begin) {
        out.push_back({k, s.substr(begin, i - begin), line, begin});
        for (size_t j = begin; j < i; ++j) line += s[j] == '\n';
    };
    static const char* multi[] = {"<<=", ">>=", "++", "--", "+=", "-=", "*=",
                                  "/=",  "%=",  "&=", "|=", "^=", "<<", ">>",
                                  "<=",  ">=",  "==", "!=", "&&", "||", "^^"};
    while (i < s.size()) {
        const size_t b = i;
        const char c = s[i];
        if (std::isspace(static_cast<unsigned char>(c))) {
            while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) {
                if (s[i] == '\n') lineStart = true;
                ++i;
            }
            push(Token::Space, b);
            continue;
        }
        if (c == '#' && lineStart) {
            while (i < s.size() && s[i] != '\n') i += s[i] == '\\' && i + 1 < s.size() ? 2 : 1;
            push(Token::Preprocessor, b);
            continue;
        }
        lineStart = false;
        if (c == '/' && i + 1 < s.size() && s[i + 1] == '/') {
            while (i < s.size() && s[i] != '\n') ++i;
            push(Token::Comment, b);
        } else if (c == '/' && i + 1 < s.size() && s[i + 1] == '*') {
            const size_t e = s.find("*/", i + 2);
            i = e == std::string::npos ? s.size() : e + 2;
            push(Token::Comment, b);
        } else if (isIdentStart(c)) {
            while (i < s.size() && isIdentChar(s[i])) ++i;
            push(Token::Identifier, b);
        } else if (std::isdigit(static_cast<unsigned char>(c)) ||
                   (c == '.' && i + 1 < s.size() &&
                    std::isdigit(static_cast<unsigned char>(s[i + 1])))) {
            if (c == '0' && i + 1 < s.size() && (s[i + 1] == 'x' || s[i + 1] == 'X')) {
                i += 2;
                while (i < s.size() && std::isxdigit(static_cast<unsigned char>(s[i]))) ++i;
            } else {
                while (i < s.size() &&
                       (std::isdigit(static_cast<unsigned char>(s[i])) || s[i] == '.'))
                    ++i;
                if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
                    ++i;
                    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
                    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
                }
            }
            while (i < s.size() && s[i] != '\0' && std::strchr("uUfFlL", s[i])) ++i;
            push(Token::Number, b);
        } else {
            size_t len = 1;
            for (const char* m : multi)
                if (s.compare(i, std::strlen(m), m) == 0) {
                    len = std::strlen(m);
                    break;
                }
            i += len;
            push(Token::Operator, b);
        }
    }
    return out;
}

namespace {

// The line `n` of a text, without its indentation.
std::string lineOf(const std::string& text, int n) {
    std::istringstream in(text);
    std::string l;
    for (int i = 1; std::getline(in, l); ++i)
        if (i == n) break;
    const size_t b = l.find_first_not_of(" \t");
    return b == std::string::npos ? "" : l.substr(b);
}

std::string flat(const std::string& text) {  // one line, single spaces
    std::string out;
    for (char c : text) {
        const bool space = std::isspace(static_cast<unsigned char>(c));
        if (space && (out.empty() || out.back() == ' ')) continue;
        out += space ? ' ' : c;
    }
    while (!out.empty() && out.back() == ' ') out.pop_back();
    return out;
}

// "line 9: `old line` -> `new line`".
std::string describeChange(const std::string& before, const std::string& after, int line) {
    return "line " + std::to_string(line) + ": `" + lineOf(before, line) + "` -> `" +
           lineOf(after, line) + "`";
}

// An edit: tokens [begin, end) of the significant list replaced by `text`.
struct Edit {
    size_t begin, end;
    std::string text;
};

class Mutator {
public:
    explicit Mutator(const std::string& source) : source_(source), tokens_(tokenizeGlsl(source)) {
        for (size_t i = 0; i < tokens_.size(); ++i)
            if (tokens_[i].kind == Token::Identifier || tokens_[i].kind == Token::Number ||
                tokens_[i].kind == Token::Operator)
                sig_.push_back(i);
        // Nesting depth of () and [] at each significant token (a bracket counts outside).
        int depth = 0;
        for (size_t k = 0; k < sig_.size(); ++k) {
            const std::string& t = text(k);
            if (t == ")" || t == "]") --depth;
            depth_.push_back(depth);
            if (t == "(" || t == "[") ++depth;
        }
    }

    std::vector<Mutant> run() {
        operators();
        constants();
        pi();
        guards();
        swaps();
        squares();
        removals();
        conditions();
        fixedArguments();
        terms();
        ternaries();
        swizzles();
        signs();
        // Unique texts, none equal to the original.
        std::vector<Mutant> out;
        std::set<std::string> seen{source_};
        for (Mutant& m : mutants_)
            if (seen.insert(m.text).second) out.push_back(std::move(m));
        return out;
    }

private:
    const std::string& text(size_t k) const { return tokens_[sig_[k]].text; }
    Token::Kind kind(size_t k) const { return tokens_[sig_[k]].kind; }
    int line(size_t k) const { return tokens_[sig_[k]].line; }
    bool is(size_t k, const char* t) const { return k < sig_.size() && text(k) == t; }

    static bool keyword(const std::string& t) {
        static const std::set<std::string> k = {"if",     "for",     "while", "return",   "else",
                                                "switch", "case",    "break", "continue", "do",
                                                "const",  "uniform", "in",    "out",      "inout"};
        return k.count(t) > 0;
    }
    static bool typeName(const std::string& t) {
        static const std::set<std::string> k = {"float", "int",  "uint",  "bool",  "vec2",
                                                "vec3",  "vec4", "ivec2", "ivec3", "uvec2",
                                                "mat3",  "mat4", "void"};
        return k.count(t) > 0;
    }
    // Whether the operator at k is binary: what precedes it ends an operand.
    bool binaryAt(size_t k) const {
        if (k == 0) return false;
        const size_t p = k - 1;
        if (kind(p) == Token::Number) return true;
        if (kind(p) == Token::Identifier) return !keyword(text(p));
        return text(p) == ")" || text(p) == "]" || text(p) == "++" || text(p) == "--";
    }
    // The end (exclusive) of the operand expression that starts at k, at its depth: up to a
    // delimiter or an operator of lower precedence than `stopAtAdditive` allows.
    size_t operandEnd(size_t k, bool stopAtAdditive) const {
        const int d = depth_[k];
        size_t e = k;
        while (e < sig_.size()) {
            if (depth_[e] < d) break;
            if (depth_[e] == d) {
                const std::string& t = text(e);
                // (A bracket at this depth opens or closes a group inside the operand; the
                // enclosing ones are at a lower depth.)
                if (t == ";" || t == "," || t == "?" || t == ":" || t == "{" || t == "}" ||
                    t == "=" || t == "+=" || t == "-=" || t == "*=" || t == "/=" || t == "<" ||
                    t == ">" || t == "<=" || t == ">=" || t == "==" || t == "!=" || t == "&&" ||
                    t == "||")
                    break;
                if (stopAtAdditive && e > k && (t == "+" || t == "-") && binaryAt(e)) break;
            }
            ++e;
        }
        return e;
    }
    // The start of the additive chain that contains the operator at k (same depth).
    size_t chainStart(size_t k) const {
        const int d = depth_[k];
        size_t b = k;
        while (b > 0) {
            const size_t p = b - 1;
            if (depth_[p] < d) break;
            if (depth_[p] == d) {
                const std::string& t = text(p);
                if (t == ";" || t == "," || t == "?" || t == ":" || t == "{" || t == "}" ||
                    t == "=" || t == "+=" || t == "-=" || t == "*=" || t == "/=" || t == "<" ||
                    t == ">" || t == "<=" || t == ">=" || t == "==" || t == "!=" || t == "&&" ||
                    t == "||" || (kind(p) == Token::Identifier && text(p) == "return"))
                    break;
            }
            b = p;
        }
        return b;
    }
    std::string span(size_t b, size_t e) const {  // significant tokens b..e, with their spacing
        if (b >= e) return "";
        std::string out;
        for (size_t i = sig_[b]; i <= sig_[e - 1]; ++i)
            out += tokens_[i].kind == Token::Comment ? " " : tokens_[i].text;
        return out;
    }
    // The arguments of the call whose "(" is at k: [begin, end) per argument, and the ")".
    bool arguments(size_t open, std::vector<std::pair<size_t, size_t>>& args, size_t& close) const {
        const int d = depth_[open];
        size_t start = open + 1;
        for (size_t e = open + 1; e < sig_.size(); ++e) {
            if (depth_[e] == d && text(e) == ")") {
                if (e > start) args.push_back({start, e});
                close = e;
                return true;
            }
            if (depth_[e] == d + 1 && text(e) == ",") {
                args.push_back({start, e});
                start = e + 1;
            }
        }
        return false;
    }

    // The text with the edits made; between significant tokens first and last (all: the
    // whole file).
    std::string apply(std::vector<Edit> edits, size_t first = 0, size_t last = size_t(-1)) const {
        std::sort(edits.begin(), edits.end(),
                  [](const Edit& a, const Edit& b) { return a.begin < b.begin; });
        const bool whole = last == size_t(-1);
        const size_t endToken = whole ? tokens_.size() : sig_[last - 1] + 1;
        std::string out;
        size_t token = whole ? 0 : sig_[first];
        for (const Edit& e : edits) {
            const size_t from = sig_[e.begin];
            for (; token < from; ++token) out += tokens_[token].text;
            // A removal takes the blank before it along: "a + b" -> "a", not "a ".
            if (e.text.empty())
                while (!out.empty() && out.back() == ' ') out.pop_back();
            out += e.text;
            token = e.end > e.begin ? sig_[e.end - 1] + 1 : from;
            if (e.text.empty() && !out.empty() && out.back() == '(' && token < tokens_.size() &&
                tokens_[token].kind == Token::Space &&
                tokens_[token].text.find('\n') == std::string::npos)
                ++token;  // "(1.0 - x)" -> "(x)"
        }
        for (; token < endToken; ++token) out += tokens_[token].text;
        return out;
    }

    void add(const char* family, size_t at, std::vector<Edit> edits) {
        Mutant m;
        m.family = family;
        m.line = line(at);
        // The edited tokens with two of context each side, before and after.
        size_t b = sig_.size(), e = 0;
        for (const Edit& x : edits) b = std::min(b, x.begin), e = std::max(e, x.end);
        auto boundary = [&](size_t k) { return is(k, ";") || is(k, "{") || is(k, "}"); };
        for (int k = 0; k < 2 && b > 0 && !boundary(b - 1); ++k) --b;
        for (int k = 0; k < 2 && e < sig_.size() && !boundary(e); ++k) ++e;
        m.change = "`" + flat(apply(edits, b, e)) + "` for `" + flat(span(b, e)) + "`";
        m.text = apply(std::move(edits));
        m.description = describeChange(source_, m.text, m.line);
        mutants_.push_back(std::move(m));
    }

    static std::string formatFloat(double v) {
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.9g", v);
        std::string s = buf;
        if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
        return s;
    }

    void operators() {
        for (size_t k = 0; k < sig_.size(); ++k) {
            const std::string& t = text(k);
            static const std::pair<const char*, const char*> swapsOf[] = {
                {"+", "-"}, {"-", "+"}, {"*", "/"}, {"/", "*"}};
            for (const auto& [from, to] : swapsOf)
                if (t == from && binaryAt(k)) add("operator", k, {{k, k + 1, to}});
            static const std::pair<const char*, const char*> compound[] = {
                {"+=", "-="}, {"-=", "+="}, {"*=", "/="}, {"/=", "*="}};
            for (const auto& [from, to] : compound)
                if (t == from) add("operator", k, {{k, k + 1, to}});
        }
    }

    void constants() {
        for (size_t k = 0; k < sig_.size(); ++k) {
            if (kind(k) != Token::Number) continue;
            std::string t = text(k);
            std::string suffix;
            while (!t.empty() && std::strchr("uUfFlL", t.back()))
                suffix = t.back() + suffix, t.pop_back();
            const bool isFloat =
                t.find_first_of(".eE") != std::string::npos && t.rfind("0x", 0) != 0;
            if (isFloat) {
                const double v = std::strtod(t.c_str(), nullptr);
                if (v == 0) continue;
                const double pi = std::numbers::pi;
                for (double f : {2.0, 0.5, pi, 1 / pi, 1.1, 0.9})
                    add("constant", k, {{k, k + 1, formatFloat(v * f) + suffix}});
            } else {
                const long v = std::strtol(t.c_str(), nullptr, 0);
                add("constant", k, {{k, k + 1, std::to_string(v + 1) + suffix}});
                if (v > 0) add("constant", k, {{k, k + 1, std::to_string(v - 1) + suffix}});
            }
        }
    }

    void pi() {
        for (size_t k = 0; k < sig_.size(); ++k)
            if (kind(k) == Token::Identifier && text(k) == "PI") add("pi", k, {{k, k + 1, "1.0"}});
    }

    void guards() {
        for (size_t k = 0; k + 1 < sig_.size(); ++k) {
            if (kind(k) != Token::Identifier || !is(k + 1, "(")) continue;
            const std::string& f = text(k);
            if (f != "max" && f != "min" && f != "clamp" && f != "abs") continue;
            std::vector<std::pair<size_t, size_t>> args;
            size_t close = 0;
            if (!arguments(k + 1, args, close) || args.empty()) continue;
            // max(a, b) -> a and -> b; clamp(x, lo, hi) -> x; abs(x) -> x.
            add("guard", k, {{k, close + 1, "(" + span(args[0].first, args[0].second) + ")"}});
            if ((f == "max" || f == "min") && args.size() == 2)
                add("guard", k, {{k, close + 1, "(" + span(args[1].first, args[1].second) + ")"}});
        }
    }

    void swaps() {
        static const std::set<std::string> commutative = {"max", "min", "dot", "distance"};
        for (size_t k = 0; k + 1 < sig_.size(); ++k) {
            if (kind(k) != Token::Identifier || !is(k + 1, "(") || keyword(text(k)) ||
                commutative.count(text(k)))
                continue;
            if (k > 0 && typeName(text(k - 1))) continue;  // a declaration, not a call
            std::vector<std::pair<size_t, size_t>> args;
            size_t close = 0;
            if (!arguments(k + 1, args, close)) continue;
            for (size_t a = 0; a + 1 < args.size(); ++a) {
                const std::string x = span(args[a].first, args[a].second),
                                  y = span(args[a + 1].first, args[a + 1].second);
                if (x == y) continue;
                add("swap", k,
                    {{args[a].first, args[a].second, y},
                     {args[a + 1].first, args[a + 1].second, x}});
            }
        }
    }

    void squares() {
        for (size_t k = 0; k + 2 < sig_.size(); ++k) {
            // x * x -> x
            if (kind(k) == Token::Identifier && is(k + 1, "*") &&
                kind(k + 2) == Token::Identifier && text(k) == text(k + 2) &&
                !(k > 0 && (is(k - 1, ".") || is(k - 1, "*"))) && !is(k + 3, "."))
                add("square", k, {{k, k + 3, text(k)}});
            // pow(x, 2.0) -> x
            if (text(k) == "pow" && is(k + 1, "(")) {
                std::vector<std::pair<size_t, size_t>> args;
                size_t close = 0;
                if (arguments(k + 1, args, close) && args.size() == 2 &&
                    std::strtod(span(args[1].first, args[1].second).c_str(), nullptr) == 2.0)
                    add("square", k,
                        {{k, close + 1, "(" + span(args[0].first, args[0].second) + ")"}});
            }
        }
        // A square added: return E; and = E; as (E) * (E).
        for (size_t k = 0; k + 1 < sig_.size(); ++k) {
            if (!(text(k) == "return" || (text(k) == "=" && depth_[k] == 0))) continue;
            const size_t b = k + 1, e = operandEnd(b, false);
            if (e <= b || !is(e, ";")) continue;
            const std::string x = span(b, e);
            add("square", k, {{b, e, "(" + x + ") * (" + x + ")"}});
        }
    }

    void removals() {
        for (size_t k = 0; k + 1 < sig_.size(); ++k) {
            if (kind(k) != Token::Identifier || !is(k + 1, "(")) continue;
            const std::string& f = text(k);
            if (f != "normalize" && f != "sqrt") continue;
            std::vector<std::pair<size_t, size_t>> args;
            size_t close = 0;
            if (!arguments(k + 1, args, close) || args.size() != 1) continue;
            add(f == "normalize" ? "normalize" : "sqrt", k,
                {{k, close + 1, "(" + span(args[0].first, args[0].second) + ")"}});
        }
        // An accumulation dropped: x += E; removed.
        for (size_t k = 0; k + 1 < sig_.size(); ++k) {
            if (!(text(k) == "+=" || text(k) == "-=")) continue;
            size_t b = k;
            while (b > 0 && !is(b - 1, ";") && !is(b - 1, "{") && !is(b - 1, "}") &&
                   !is(b - 1, ")"))
                --b;
            size_t e = k;
            while (e < sig_.size() && !is(e, ";")) ++e;
            // ";" stays: the statement may be the body of a loop without braces.
            if (e < sig_.size() && depth_[k] == 0) add("term", k, {{b, e + 1, ";"}});
        }
    }

    void conditions() {
        for (size_t k = 0; k + 1 < sig_.size(); ++k) {
            static const std::pair<const char*, const char*> negations[] = {
                {"<", ">="}, {">", "<="}, {"<=", ">"}, {">=", "<"}, {"==", "!="}, {"!=", "=="}};
            for (const auto& [from, to] : negations)
                if (text(k) == from) add("condition", k, {{k, k + 1, to}});
            if (text(k) == "if" && is(k + 1, "(")) {
                std::vector<std::pair<size_t, size_t>> args;
                size_t close = 0;
                if (arguments(k + 1, args, close)) add("condition", k, {{k + 2, close, "true"}});
            }
        }
    }

    void fixedArguments() {
        // Each parameter of each function defined here, replaced in its body by a constant:
        // an argument ignored (a sample count fixed at 64, roughness at 0.5, N at +z).
        for (size_t k = 0; k + 2 < sig_.size(); ++k) {
            if (!typeName(text(k)) || kind(k + 1) != Token::Identifier || !is(k + 2, "(")) continue;
            std::vector<std::pair<size_t, size_t>> params;
            size_t close = 0;
            if (!arguments(k + 2, params, close) || !is(close + 1, "{")) continue;
            size_t bodyEnd = close + 1;
            for (int braces = 0; bodyEnd < sig_.size(); ++bodyEnd) {
                braces += is(bodyEnd, "{") - is(bodyEnd, "}");
                if (braces == 0) break;
            }
            for (const auto& [pb, pe] : params) {
                if (pe - pb < 2) continue;
                const std::string type = text(pe - 2), name = text(pe - 1);
                static const std::pair<const char*, const char*> fixed[] = {
                    {"float", "0.5"},
                    {"uint", "64u"},
                    {"int", "64"},
                    {"vec2", "vec2(0.5)"},
                    {"vec3", "vec3(0.0, 0.0, 1.0)"},
                    {"vec4", "vec4(0.0, 0.0, 1.0, 1.0)"}};
                for (const auto& [t, value] : fixed) {
                    if (type != t) continue;
                    std::vector<Edit> edits;
                    for (size_t j = close + 1; j < bodyEnd; ++j)
                        if (kind(j) == Token::Identifier && text(j) == name &&
                            !(j > 0 && is(j - 1, ".")))
                            edits.push_back({j, j + 1, value});
                    if (!edits.empty()) add("argument", edits.front().begin, edits);
                }
            }
        }
    }

    void terms() {
        for (size_t k = 0; k < sig_.size(); ++k) {
            if (!((text(k) == "+" || text(k) == "-") && binaryAt(k))) continue;
            // Drop the term after the operator.
            const size_t e = operandEnd(k + 1, true);
            if (e > k + 1) add("term", k, {{k, e, ""}});
            // The first operator of a chain: drop the term before it too (a '-' stays, unary).
            const size_t b = chainStart(k);
            bool first = true;
            for (size_t j = b; j < k && first; ++j)
                if (depth_[j] == depth_[k] && (text(j) == "+" || text(j) == "-") && binaryAt(j))
                    first = false;
            if (first && b < k) {
                add("term", k, {{b, k + (text(k) == "+" ? 1 : 0), ""}});
                // 1.0 - x -> x: the complement dropped.
                if (k == b + 1 && text(k) == "-" && kind(b) == Token::Number &&
                    std::strtod(text(b).c_str(), nullptr) == 1.0)
                    add("complement", k, {{b, k + 1, ""}});
            }
        }
    }

    void ternaries() {
        for (size_t q = 0; q < sig_.size(); ++q) {
            if (text(q) != "?") continue;
            const int d = depth_[q];
            size_t colon = q + 1;
            for (int nested = 0; colon < sig_.size(); ++colon) {
                if (depth_[colon] != d) continue;
                if (text(colon) == "?") ++nested;
                if (text(colon) == ":" && nested-- == 0) break;
            }
            if (colon >= sig_.size()) continue;
            size_t e = colon + 1;
            while (e < sig_.size() &&
                   !(depth_[e] <= d && (is(e, ";") || is(e, ")") || is(e, ",") || is(e, ":"))))
                ++e;
            const std::string a = span(q + 1, colon), b = span(colon + 1, e);
            if (a == b) continue;
            add("ternary", q, {{q + 1, colon, b}, {colon + 1, e, a}});
        }
    }

    void swizzles() {
        for (size_t k = 1; k < sig_.size(); ++k) {
            if (!is(k - 1, ".") || kind(k) != Token::Identifier) continue;
            const std::string& t = text(k);
            static const std::pair<const char*, const char*> swaps[] = {
                {"x", "y"}, {"y", "x"},   {"z", "x"},   {"r", "g"},     {"g", "r"},
                {"b", "r"}, {"xy", "yx"}, {"rg", "gr"}, {"xyz", "zyx"}, {"rgb", "bgr"}};
            for (const auto& [from, to] : swaps)
                if (t == from) add("swizzle", k, {{k, k + 1, to}});
        }
    }

    void signs() {
        for (size_t k = 0; k + 1 < sig_.size(); ++k)
            if (text(k) == "-" && !binaryAt(k)) add("sign", k, {{k, k + 1, ""}});
    }

    const std::string& source_;
    std::vector<Token> tokens_;
    std::vector<size_t> sig_;  // indices of significant tokens
    std::vector<int> depth_;
    std::vector<Mutant> mutants_;
};

}  // namespace

const std::vector<MutantFamily>& mutantFamilies() {
    static const std::vector<MutantFamily> f = {
        {"operator", "+ and -, * and / swapped (also in += -= *= /=)", "an operation inverted"},
        {"constant", "a literal x2, /2, xPI, /PI, x1.1, x0.9 (integers +-1)", "a constant off"},
        {"pi", "PI removed (1.0)", "PI missing"},
        {"guard", "a max/min/clamp/abs dropped (its first or second argument left)",
         "a clamp or guard missing"},
        {"swap", "two arguments of a call, or two components of a constructor, swapped",
         "arguments or components swapped"},
        {"square", "a square removed (x * x, pow(x, 2.0)) or added to a returned/assigned value",
         "a square missing or extra"},
        {"normalize", "normalize() removed", "a normalisation missing"},
        {"sqrt", "sqrt() removed", "a square root missing"},
        {"term", "a term of a sum dropped, or an accumulation (+=, -=) removed", "a term missing"},
        {"complement", "1.0 - x turned into x", "x where 1 - x belongs"},
        {"condition", "a comparison negated, or an if's condition made true",
         "a condition reversed or missing"},
        {"argument", "a parameter ignored (fixed: samples 64, a float 0.5, a vector +z)",
         "an argument ignored"},
        {"ternary", "the two branches of a ? : swapped", "the two cases of a choice swapped"},
        {"swizzle", "a component swapped (.x/.y, .rg/.gr, ...)", "a wrong component"},
        {"sign", "a unary minus removed", "a sign missing"},
    };
    return f;
}

std::vector<Mutant> generateMutants(const std::string& solution) {
    return Mutator(solution).run();
}

Mutant mutantFromEdits(const std::string& family, const std::string& source,
                       std::vector<TextEdit> edits) {
    std::sort(edits.begin(), edits.end(),
              [](const TextEdit& a, const TextEdit& b) { return a.begin < b.begin; });
    Mutant m;
    m.family = family;
    size_t at = 0;
    for (const TextEdit& e : edits) {
        m.text += source.substr(at, e.begin - at) + e.text;
        at = e.end;
    }
    m.text += source.substr(at);
    m.line = 1 + int(std::count(source.begin(), source.begin() + long(edits.front().begin), '\n'));
    // The change, each distinct edit once: "`min(n, 512u)` for `n` (3 places)".
    std::vector<std::pair<std::string, int>> changes;
    for (const TextEdit& e : edits) {
        const std::string one =
            "`" + flat(e.text) + "` for `" + flat(source.substr(e.begin, e.end - e.begin)) + "`";
        if (!changes.empty() && changes.back().first == one)
            ++changes.back().second;
        else
            changes.push_back({one, 1});
    }
    for (const auto& [one, places] : changes)
        m.change += (m.change.empty() ? "" : "; ") + one +
                    (places > 1 ? " (" + std::to_string(places) + " places)" : "");
    m.description = describeChange(source, m.text, m.line);
    return m;
}

}  // namespace pbrlab
