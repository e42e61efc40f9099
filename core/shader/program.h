// Linked GLSL programs, built from ShaderParts and cached by (parts, sorted define set), with
// change detection on every file that went in (hot reload).
#pragma once

#include <filesystem>
#include <functional>
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "gl/objects.h"
#include "shader/preprocess.h"
#include "util/error.h"
#include "util/fs.h"

namespace pbrlab {

class Program {
public:
    Program(gl::Handle handle, std::vector<std::filesystem::path> files,
            std::vector<LoopSite> loops = {});
    GLuint id() const { return handle_.id(); }
    void use() const { gl::UseProgram(id()); }

    // -1 when the program does not use the uniform (the compiler removed it or it never
    // existed): callers use this to skip work nobody samples.
    GLint location(const std::string& name) const;
    bool uses(const std::string& name) const { return location(name) >= 0; }
    void set(const std::string& name, float v) const;
    void set(const std::string& name, int v) const;
    void setUnsigned(const std::string& name, unsigned v) const;
    void set(const std::string& name, const glm::vec2& v) const;
    void set(const std::string& name, const glm::vec3& v) const;
    void set(const std::string& name, const glm::vec4& v) const;
    void set(const std::string& name, const glm::mat4& v) const;
    void set(const std::string& name, const std::vector<glm::vec3>& v) const;

    // True when a file that went into this program changed on disk since it was built.
    bool sourcesChanged() const;
    void refreshStamps();
    const std::vector<std::filesystem::path>& files() const { return files_; }
    // The loops of the students' files in the fragment shader (ExpandedShader::loops).
    const std::vector<LoopSite>& loops() const { return loops_; }

private:
    gl::Handle handle_;
    std::vector<std::filesystem::path> files_;
    std::vector<LoopSite> loops_;
    std::vector<FileStamp> stamps_;
    mutable std::unordered_map<std::string, GLint> locations_;
};

struct ProgramRecipe {
    std::string label;  // what the program is, for listings ("G-buffer", "view ndotl")
    std::vector<ShaderPart> vertex;
    std::vector<ShaderPart> fragment;
    Defines defines;
    std::string key() const;  // parts and sorted defines, as one string
};

// One compile the cache did: which program, which permutation, how long it took.
struct CompiledProgram {
    std::string label;
    std::string defines;  // sorted "NAME=value" pairs, space-separated ("" when none)
    double milliseconds = 0;
};

class ProgramCache {
public:
    explicit ProgramCache(ShaderPreprocessor preprocessor) : pre_(std::move(preprocessor)) {}

    // The cached program for this recipe, compiled on first use. Throws ShaderError.
    std::shared_ptr<Program> get(const ProgramRecipe& recipe);
    // Recompiles when a source changed. On failure the cached (last good) program stays and
    // the error is rethrown, so a caller can keep showing the old image with the log.
    std::shared_ptr<Program> reloadIfChanged(const ProgramRecipe& recipe);

    int compileCount() const { return compiles_; }  // observable: tests count compiles
    // Every compile so far, in order (a hot reload appears again).
    const std::vector<CompiledProgram>& compiled() const { return compiled_; }
    const ShaderPreprocessor& preprocessor() const { return pre_; }

private:
    std::shared_ptr<Program> build(const ProgramRecipe& recipe);
    ShaderPreprocessor pre_;
    std::map<std::string, std::shared_ptr<Program>> programs_;
    int compiles_ = 0;
    std::vector<CompiledProgram> compiled_;
};

// "NAME=value NAME2=value2", sorted (Defines is an ordered map).
std::string definesText(const Defines& defines);

}  // namespace pbrlab
