#include "shader/program.h"

#include <chrono>
#include <cstdio>
#include <glm/gtc/type_ptr.hpp>

#include "util/log.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

std::string shaderLog(GLuint shader) {
    GLint length = 0;
    gl::GetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(size_t(std::max(length, 1)), '\0');
    gl::GetShaderInfoLog(shader, length, nullptr, log.data());
    return log.c_str();
}

std::string programLog(GLuint program) {
    GLint length = 0;
    gl::GetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(size_t(std::max(length, 1)), '\0');
    gl::GetProgramInfoLog(program, length, nullptr, log.data());
    return log.c_str();
}

gl::Handle compile(GLenum stage, const ExpandedShader& source) {
    gl::Handle shader(gl::CreateShader(stage), [](GLuint id) { gl::DeleteShader(id); });
    const char* text = source.text.c_str();
    gl::ShaderSource(shader.id(), 1, &text, nullptr);
    gl::CompileShader(shader.id());
    GLint ok = 0;
    gl::GetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
    if (!ok) throw ShaderError(mapCompilerLog(shaderLog(shader.id()), source));
    return shader;
}

std::string partsKey(const std::vector<ShaderPart>& parts) {
    std::string key;
    for (const auto& p : parts)
        key += (p.text.empty() ? p.file.string()
                               : p.name + "#" + std::to_string(std::hash<std::string>{}(p.text))) +
               "|";
    return key;
}

}  // namespace

Program::Program(gl::Handle handle, std::vector<fs::path> files, std::vector<LoopSite> loops)
    : handle_(std::move(handle)), files_(std::move(files)), loops_(std::move(loops)) {
    for (const auto& f : files_) stamps_.push_back(FileStamp::of(f));
}

GLint Program::location(const std::string& name) const {
    auto it = locations_.find(name);
    if (it != locations_.end()) return it->second;
    GLint loc = gl::GetUniformLocation(id(), name.c_str());
    locations_.emplace(name, loc);
    return loc;
}

void Program::set(const std::string& name, float v) const {
    gl::Uniform1f(location(name), v);
}
void Program::set(const std::string& name, int v) const {
    gl::Uniform1i(location(name), v);
}
void Program::setUnsigned(const std::string& name, unsigned v) const {
    gl::Uniform1ui(location(name), v);
}
void Program::set(const std::string& name, const glm::vec2& v) const {
    gl::Uniform2f(location(name), v.x, v.y);
}
void Program::set(const std::string& name, const glm::vec3& v) const {
    gl::Uniform3f(location(name), v.x, v.y, v.z);
}
void Program::set(const std::string& name, const glm::vec4& v) const {
    gl::Uniform4f(location(name), v.x, v.y, v.z, v.w);
}
void Program::set(const std::string& name, const glm::mat4& v) const {
    gl::UniformMatrix4fv(location(name), 1, GL_FALSE, glm::value_ptr(v));
}
void Program::set(const std::string& name, const std::vector<glm::vec3>& v) const {
    if (!v.empty()) gl::Uniform3fv(location(name), GLsizei(v.size()), glm::value_ptr(v[0]));
}

void Program::refreshStamps() {
    for (size_t i = 0; i < files_.size(); ++i) stamps_[i] = FileStamp::of(files_[i]);
}

bool Program::sourcesChanged() const {
    for (size_t i = 0; i < files_.size(); ++i)
        if (FileStamp::of(files_[i]) != stamps_[i]) return true;
    return false;
}

std::string ProgramRecipe::key() const {
    std::string k = partsKey(vertex) + "/" + partsKey(fragment) + "/";
    for (const auto& [name, value] : defines) k += name + "=" + value + ";";
    return k;
}

std::string definesText(const Defines& defines) {
    std::string d;
    for (const auto& [name, value] : defines) d += (d.empty() ? "" : " ") + name + "=" + value;
    return d;
}

std::shared_ptr<Program> ProgramCache::build(const ProgramRecipe& recipe) {
    const auto start = std::chrono::steady_clock::now();
    ExpandedShader vs = pre_.expand(recipe.vertex, recipe.defines);
    ExpandedShader fs = pre_.expand(recipe.fragment, recipe.defines);
    gl::Handle vertex = compile(GL_VERTEX_SHADER, vs);
    gl::Handle fragment = compile(GL_FRAGMENT_SHADER, fs);
    gl::Handle program(gl::CreateProgram(), [](GLuint id) { gl::DeleteProgram(id); });
    gl::AttachShader(program.id(), vertex.id());
    gl::AttachShader(program.id(), fragment.id());
    gl::LinkProgram(program.id());
    GLint ok = 0;
    gl::GetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    if (!ok) throw ShaderError(mapCompilerLog(programLog(program.id()), fs));
    ++compiles_;
    countEvent(Counter::ProgramCompiles);
    std::vector<fs::path> files = vs.files;
    files.insert(files.end(), fs.files.begin(), fs.files.end());
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    compiled_.push_back(
        {recipe.label.empty() ? "(unnamed)" : recipe.label, definesText(recipe.defines), ms});
    char time[32];
    std::snprintf(time, sizeof time, "%.1f ms", ms);
    logLine("compile", "#" + std::to_string(compiles_) + " " + compiled_.back().label + " {" +
                           compiled_.back().defines + "} " + time);
    return std::make_shared<Program>(std::move(program), std::move(files), std::move(fs.loops));
}

std::shared_ptr<Program> ProgramCache::get(const ProgramRecipe& recipe) {
    std::string key = recipe.key();
    auto it = programs_.find(key);
    if (it != programs_.end()) return it->second;
    auto program = build(recipe);
    programs_.emplace(key, program);
    return program;
}

std::shared_ptr<Program> ProgramCache::reloadIfChanged(const ProgramRecipe& recipe) {
    std::string key = recipe.key();
    auto it = programs_.find(key);
    if (it == programs_.end()) return get(recipe);
    if (!it->second->sourcesChanged()) return it->second;
    std::shared_ptr<Program> program;
    try {
        program = build(recipe);
    } catch (const Error&) {
        it->second->refreshStamps();  // the old program stays; retry on the next change
        throw;
    }
    it->second = program;
    return program;
}

}  // namespace pbrlab
