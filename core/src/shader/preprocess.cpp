#include "shader/preprocess.h"

#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "pbrlab/error.h"
#include "shader/student_file.h"

namespace fs = std::filesystem;

namespace pbrlab {

bool isInside(const fs::path& path, const fs::path& root) {
    // A path that cannot be resolved (a symlink loop, a component that is not a folder) is
    // not inside anything.
    std::error_code ec1, ec2;
    fs::path p = fs::weakly_canonical(path, ec1), r = fs::weakly_canonical(root, ec2);
    if (ec1 || ec2) return false;
    auto [rootEnd, _] = std::mismatch(r.begin(), r.end(), p.begin(), p.end());
    return rootEnd == r.end();
}

ShaderPreprocessor::ShaderPreprocessor(std::vector<fs::path> roots) : roots_(std::move(roots)) {}

namespace {

std::string readText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path.string() + ": cannot open shader file");
    std::ostringstream s;
    s << in.rdbuf();
    std::string text = s.str();
    // GL reads the source as a C string: a NUL would silently cut the program short there.
    if (text.find('\0') != std::string::npos)
        throw Error(path.string() + ": contains NUL bytes (not text): refused");
    return text;
}

struct Expander {
    std::vector<fs::path> roots;
    fs::path studentFolder;  // set while expanding a student's file (see ShaderPart)
    ExpandedShader out;
    std::set<fs::path> included;

    int sourceIndex(const std::string& name) {
        out.sourceNames.push_back(name);
        return int(out.sourceNames.size() - 1);
    }

    // An include is looked up next to the including file, then in each root; whatever it
    // resolves to must stay inside a root (no "../" or symlink escapes).
    fs::path resolve(const std::string& target, const fs::path& from, const std::string& where) {
        std::vector<fs::path> candidates;
        if (!from.empty()) candidates.push_back(from.parent_path() / target);
        for (const auto& root : roots) candidates.push_back(root / target);
        for (const auto& c : candidates) {
            std::error_code ec;
            if (!fs::exists(c, ec)) {
                if (ec && ec != std::errc::no_such_file_or_directory)
                    throw Error(where + ": #include \"" + target + "\" cannot be read (" +
                                ec.message() + ")");
                continue;
            }
            bool allowed = false;
            for (const auto& root : roots) allowed = allowed || isInside(c, root);
            if (!allowed)
                throw Error(where + ": #include \"" + target +
                            "\" leaves the allowed shader folders");
            fs::path resolved = fs::canonical(c, ec);
            if (ec)
                throw Error(where + ": #include \"" + target + "\" cannot be resolved (" +
                            ec.message() + ")");
            return resolved;
        }
        throw Error(where + ": #include \"" + target + "\" not found");
    }

    std::string read(const fs::path& file) const {
        return studentFolder.empty() ? readText(file) : readStudentFile(file, studentFolder);
    }

    void expandText(const std::string& text, const std::string& name, const fs::path& file) {
        int index = sourceIndex(name);
        out.text += "#line 1 " + std::to_string(index) + "\n";
        static const std::regex includeLine(R"(^\s*#\s*include\s*"([^"]+)\"\s*(//.*)?$)");
        static const std::regex versionLine(R"(^\s*#\s*version\b.*$)");
        std::istringstream in(text);
        std::string line;
        int lineNo = 0;
        while (std::getline(in, line)) {
            ++lineNo;
            if (!line.empty() && line.back() == '\r') line.pop_back();
            std::smatch m;
            if (std::regex_match(line, m, includeLine)) {
                std::string where = name + ":" + std::to_string(lineNo);
                fs::path target = resolve(m[1].str(), file, where);
                if (included.insert(target).second) {
                    out.files.push_back(target);
                    expandText(read(target), target.string(), target);
                }
                out.text +=
                    "#line " + std::to_string(lineNo + 1) + " " + std::to_string(index) + "\n";
            } else if (std::regex_match(line, versionLine)) {
                out.text += "\n";  // the host writes #version once, first
            } else {
                out.text += line + "\n";
            }
        }
    }
};

}  // namespace

ExpandedShader ShaderPreprocessor::expand(const std::vector<ShaderPart>& parts,
                                          const Defines& defines) const {
    Expander ex{roots_, {}, {}, {}};
    ex.out.text = "#version 450 core\n";
    for (const auto& [name, value] : defines) ex.out.text += "#define " + name + " " + value + "\n";
    for (const auto& part : parts) {
        if (!part.text.empty() || part.file.empty()) {
            ex.roots = roots_;
            ex.studentFolder.clear();
            ex.expandText(part.text, part.name.empty() ? "<generated>" : part.name, {});
            continue;
        }
        std::error_code ec;
        fs::path file = fs::weakly_canonical(part.file, ec);
        if (ec) throw Error(part.file.string() + ": cannot be resolved (" + ec.message() + ")");
        if (!ex.included.insert(file).second) continue;
        ex.out.files.push_back(file);
        ex.studentFolder = part.studentFolder;
        ex.roots = part.studentFolder.empty() ? roots_ : std::vector<fs::path>{part.studentFolder};
        // A student's file is read by the name it was given, so that the screening sees a
        // link as a link (and names the file as the student knows it).
        ex.expandText(ex.read(part.studentFolder.empty() ? file : part.file), file.string(), file);
    }
    return ex.out;
}

std::string mapCompilerLog(const std::string& log, const std::vector<std::string>& sourceNames) {
    // Mesa writes "0:12(5): error: ...", others "0(12) : error ...".
    static const std::regex ref(R"((^|\n|\s)(\d+)(:(\d+)\((\d+)\)|\((\d+)\)))");
    std::string result;
    auto begin = log.cbegin();
    std::smatch m;
    while (std::regex_search(begin, log.cend(), m, ref)) {
        result.append(begin, m[0].first);
        size_t index = std::stoul(m[2].str());
        std::string name = index < sourceNames.size() ? sourceNames[index] : m[2].str();
        result += m[1].str() + name + ":" +
                  (m[4].matched ? m[4].str() + "(" + m[5].str() + ")" : m[6].str());
        begin = m[0].second;
    }
    result.append(begin, log.cend());
    return result;
}

}  // namespace pbrlab
