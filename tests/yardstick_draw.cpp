// Yardstick for `pbrlab render ndotl --size 256x256` (scripts/bench.sh, issue 46): the least a
// headless GL program can do for one picture. It creates an OSMesa context, compiles a trivial
// shader pair, draws one full-screen triangle into a 256x256 RGBA8 buffer and reads it back,
// and prints the centre pixel. It is timed as a whole process beside pbrlab, so that pbrlab's
// time is read as a ratio to a floor that moves with the machine (load, Mesa's version) but not
// with pbrlab's code: keep it stand-alone (no pbrlab code) and free of anything a draw does not
// need.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>

#include <cstdio>
#include <vector>

namespace {

constexpr int kSize = 256;

const char* const kVertexShader = R"(#version 330 core
void main() {
    // One triangle that covers the viewport: (-1,-1), (3,-1), (-1,3).
    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    gl_Position = vec4(p, 0.0, 1.0);
}
)";

const char* const kFragmentShader = R"(#version 330 core
out vec4 color;
void main() {
    color = vec4(gl_FragCoord.xy / 256.0, 0.25, 1.0);
}
)";

GLuint compile(GLenum type, const char* source) {
    GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        std::fprintf(stderr, "yardstick_draw: shader does not compile: %s\n", log);
        return 0;
    }
    return shader;
}

OSMesaContext createContext() {
    // A 3.3 core context, the least this draw needs (Mesa gives its highest core version);
    // where OSMesa cannot make a core context, its default one.
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           0,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           3,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           3,
                           0};
    OSMesaContext context = OSMesaCreateContextAttribs(attribs, nullptr);
    return context ? context : OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, nullptr);
}

}  // namespace

int main() {
    OSMesaContext context = createContext();
    if (!context) {
        std::fprintf(stderr, "yardstick_draw: OSMesa could not create a context\n");
        return 1;
    }
    std::vector<unsigned char> buffer(4 * kSize * kSize);
    if (!OSMesaMakeCurrent(context, buffer.data(), GL_UNSIGNED_BYTE, kSize, kSize)) {
        std::fprintf(stderr, "yardstick_draw: OSMesaMakeCurrent failed\n");
        return 1;
    }
    GLuint vertex = compile(GL_VERTEX_SHADER, kVertexShader);
    GLuint fragment = compile(GL_FRAGMENT_SHADER, kFragmentShader);
    if (!vertex || !fragment) return 1;
    GLuint program = glCreateProgram();
    glAttachShader(program, vertex);
    glAttachShader(program, fragment);
    glLinkProgram(program);
    GLint linked = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    if (!linked) {
        std::fprintf(stderr, "yardstick_draw: program does not link\n");
        return 1;
    }
    // A core context draws only with a vertex array bound, even one without attributes.
    GLuint vertexArray = 0;
    glGenVertexArrays(1, &vertexArray);
    glBindVertexArray(vertexArray);
    glViewport(0, 0, kSize, kSize);
    glUseProgram(program);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    std::vector<unsigned char> pixels(4 * kSize * kSize);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, kSize, kSize, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    if (glGetError() != GL_NO_ERROR) {
        std::fprintf(stderr, "yardstick_draw: GL error\n");
        return 1;
    }
    const unsigned char* centre = &pixels[4 * ((kSize / 2) * kSize + kSize / 2)];
    std::printf("%s: centre pixel %d %d %d %d\n",
                reinterpret_cast<const char*>(glGetString(GL_VERSION)), centre[0], centre[1],
                centre[2], centre[3]);
    OSMesaDestroyContext(context);
    return 0;
}
