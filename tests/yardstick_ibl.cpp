// Yardstick for `pbrlab precompute --env FILE.hdr` (scripts/bench.sh, issue 46): the image-based
// lighting precomputation as LearnOpenGL's lessons "Diffuse irradiance" and "Specular IBL"
// describe it, on the GPU through an OSMesa context, written here from the lessons' text:
//   equirectangular .hdr (stb_image) -> 512x512 RGB16F cube, 6 draws, then its mipmaps;
//   irradiance cube 32x32, hemisphere convolution with sampleDelta = 0.025;
//   prefiltered cube 128x128, 5 mips, GGX importance sampling over a Hammersley sequence,
//   1024 samples a texel, sampling the source's mips by the sample's solid angle;
//   BRDF lookup table 512x512 RG16F, 1024 samples a texel.
// pbrlab's precompute time is read as a ratio to this program's, run in the same call: a
// pipeline that moves with the machine and Mesa, never with pbrlab's code, so keep it
// stand-alone (no pbrlab code) and as the lessons have it. One difference that changes no
// texel's work: each face is drawn as one full-screen triangle whose direction comes from the
// face's axes, where the lessons draw a cube through a 90-degree projection into a framebuffer
// with a depth buffer (one triangle needs none).
// Prints the time of each stage (each ends with glFinish) and the total, one line each.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
#include <stb/stb_image.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

constexpr int kEnvironmentSize = 512, kIrradianceSize = 32, kPrefilterSize = 128,
              kPrefilterMips = 5, kLutSize = 512;

// The vertex shader of every cube pass: one triangle over the viewport, and the (unnormalised)
// direction of each texel of face uFace, by the cube map face table of the GL specification.
// The direction is linear in the viewport position, so interpolating it is exact.
const char* const kCubeVertexShader = R"(#version 330 core
uniform int uFace;
out vec3 localPos;
void main() {
    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    gl_Position = vec4(p, 0.0, 1.0);
    if (uFace == 0) localPos = vec3(1.0, -p.y, -p.x);
    else if (uFace == 1) localPos = vec3(-1.0, -p.y, p.x);
    else if (uFace == 2) localPos = vec3(p.x, 1.0, p.y);
    else if (uFace == 3) localPos = vec3(p.x, -1.0, -p.y);
    else if (uFace == 4) localPos = vec3(p.x, -p.y, 1.0);
    else localPos = vec3(-p.x, -p.y, -1.0);
}
)";

const char* const kEquirectangularShader = R"(#version 330 core
in vec3 localPos;
out vec4 FragColor;
uniform sampler2D equirectangularMap;
const vec2 invAtan = vec2(0.1591, 0.3183);
vec2 SampleSphericalMap(vec3 v) {
    vec2 uv = vec2(atan(v.z, v.x), asin(v.y));
    uv *= invAtan;
    uv += 0.5;
    return uv;
}
void main() {
    vec2 uv = SampleSphericalMap(normalize(localPos));
    FragColor = vec4(texture(equirectangularMap, uv).rgb, 1.0);
}
)";

const char* const kIrradianceShader = R"(#version 330 core
in vec3 localPos;
out vec4 FragColor;
uniform samplerCube environmentMap;
const float PI = 3.14159265359;
void main() {
    vec3 N = normalize(localPos);
    vec3 irradiance = vec3(0.0);
    vec3 up = vec3(0.0, 1.0, 0.0);
    vec3 right = normalize(cross(up, N));
    up = normalize(cross(N, right));
    float sampleDelta = 0.025;
    float nrSamples = 0.0;
    for (float phi = 0.0; phi < 2.0 * PI; phi += sampleDelta) {
        for (float theta = 0.0; theta < 0.5 * PI; theta += sampleDelta) {
            vec3 tangentSample = vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
            vec3 sampleVec = tangentSample.x * right + tangentSample.y * up + tangentSample.z * N;
            irradiance += texture(environmentMap, sampleVec).rgb * cos(theta) * sin(theta);
            nrSamples++;
        }
    }
    irradiance = PI * irradiance * (1.0 / float(nrSamples));
    FragColor = vec4(irradiance, 1.0);
}
)";

// Shared by the prefilter and the lookup table: the Hammersley sequence and GGX sampling.
const char* const kImportanceSampling = R"(
const float PI = 3.14159265359;
float RadicalInverse_VdC(uint bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return float(bits) * 2.3283064365386963e-10;
}
vec2 Hammersley(uint i, uint N) {
    return vec2(float(i) / float(N), RadicalInverse_VdC(i));
}
vec3 ImportanceSampleGGX(vec2 Xi, vec3 N, float roughness) {
    float a = roughness * roughness;
    float phi = 2.0 * PI * Xi.x;
    float cosTheta = sqrt((1.0 - Xi.y) / (1.0 + (a * a - 1.0) * Xi.y));
    float sinTheta = sqrt(1.0 - cosTheta * cosTheta);
    vec3 H = vec3(cos(phi) * sinTheta, sin(phi) * sinTheta, cosTheta);
    vec3 up = abs(N.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 tangent = normalize(cross(up, N));
    vec3 bitangent = cross(N, tangent);
    return normalize(tangent * H.x + bitangent * H.y + N * H.z);
}
)";

const char* const kPrefilterShader = R"(
in vec3 localPos;
out vec4 FragColor;
uniform samplerCube environmentMap;
uniform float roughness;
uniform float resolution;
float DistributionGGX(vec3 N, vec3 H, float roughness) {
    float a = roughness * roughness;
    float a2 = a * a;
    float NdotH = max(dot(N, H), 0.0);
    float NdotH2 = NdotH * NdotH;
    float denom = (NdotH2 * (a2 - 1.0) + 1.0);
    return a2 / (PI * denom * denom);
}
void main() {
    vec3 N = normalize(localPos);
    vec3 R = N;
    vec3 V = R;
    const uint SAMPLE_COUNT = 1024u;
    float totalWeight = 0.0;
    vec3 prefilteredColor = vec3(0.0);
    for (uint i = 0u; i < SAMPLE_COUNT; ++i) {
        vec2 Xi = Hammersley(i, SAMPLE_COUNT);
        vec3 H = ImportanceSampleGGX(Xi, N, roughness);
        vec3 L = normalize(2.0 * dot(V, H) * H - V);
        float NdotL = max(dot(N, L), 0.0);
        if (NdotL > 0.0) {
            float D = DistributionGGX(N, H, roughness);
            float NdotH = max(dot(N, H), 0.0);
            float HdotV = max(dot(H, V), 0.0);
            float pdf = D * NdotH / (4.0 * HdotV) + 0.0001;
            float saTexel = 4.0 * PI / (6.0 * resolution * resolution);
            float saSample = 1.0 / (float(SAMPLE_COUNT) * pdf + 0.0001);
            float mipLevel = roughness == 0.0 ? 0.0 : 0.5 * log2(saSample / saTexel);
            prefilteredColor += textureLod(environmentMap, L, mipLevel).rgb * NdotL;
            totalWeight += NdotL;
        }
    }
    prefilteredColor = prefilteredColor / totalWeight;
    FragColor = vec4(prefilteredColor, 1.0);
}
)";

const char* const kLutVertexShader = R"(#version 330 core
void main() {
    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    gl_Position = vec4(p, 0.0, 1.0);
}
)";

const char* const kLutShader = R"(
out vec2 FragColor;
uniform float resolution;
float GeometrySchlickGGX(float NdotV, float roughness) {
    float a = roughness;
    float k = (a * a) / 2.0;
    return NdotV / (NdotV * (1.0 - k) + k);
}
float GeometrySmith(vec3 N, vec3 V, vec3 L, float roughness) {
    float NdotV = max(dot(N, V), 0.0);
    float NdotL = max(dot(N, L), 0.0);
    return GeometrySchlickGGX(NdotV, roughness) * GeometrySchlickGGX(NdotL, roughness);
}
vec2 IntegrateBRDF(float NdotV, float roughness) {
    vec3 V = vec3(sqrt(1.0 - NdotV * NdotV), 0.0, NdotV);
    float A = 0.0;
    float B = 0.0;
    vec3 N = vec3(0.0, 0.0, 1.0);
    const uint SAMPLE_COUNT = 1024u;
    for (uint i = 0u; i < SAMPLE_COUNT; ++i) {
        vec2 Xi = Hammersley(i, SAMPLE_COUNT);
        vec3 H = ImportanceSampleGGX(Xi, N, roughness);
        vec3 L = normalize(2.0 * dot(V, H) * H - V);
        float NdotL = max(L.z, 0.0);
        float NdotH = max(H.z, 0.0);
        float VdotH = max(dot(V, H), 0.0);
        if (NdotL > 0.0) {
            float G = GeometrySmith(N, V, L, roughness);
            float G_Vis = (G * VdotH) / (NdotH * NdotV);
            float Fc = pow(1.0 - VdotH, 5.0);
            A += (1.0 - Fc) * G_Vis;
            B += Fc * G_Vis;
        }
    }
    return vec2(A, B) / float(SAMPLE_COUNT);
}
void main() {
    // The lessons' quad interpolates texture coordinates 0..1 to the pixel centres: the same.
    vec2 TexCoords = gl_FragCoord.xy / resolution;
    FragColor = IntegrateBRDF(TexCoords.x, TexCoords.y);
}
)";

using Clock = std::chrono::steady_clock;

[[noreturn]] void fail(const std::string& message) {
    std::fprintf(stderr, "yardstick_ibl: %s\n", message.c_str());
    std::exit(1);
}

GLuint compile(GLenum type, const std::string& source) {
    GLuint shader = glCreateShader(type);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        fail(std::string("shader does not compile: ") + log);
    }
    return shader;
}

GLuint program(const std::string& vertexSource, const std::string& fragmentSource) {
    GLuint vertex = compile(GL_VERTEX_SHADER, vertexSource);
    GLuint fragment = compile(GL_FRAGMENT_SHADER, fragmentSource);
    GLuint id = glCreateProgram();
    glAttachShader(id, vertex);
    glAttachShader(id, fragment);
    glLinkProgram(id);
    GLint ok = GL_FALSE;
    glGetProgramiv(id, GL_LINK_STATUS, &ok);
    if (!ok) fail("program does not link");
    glDeleteShader(vertex);
    glDeleteShader(fragment);
    return id;
}

GLuint cubeTexture(int size, GLenum minFilter) {
    GLuint texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_CUBE_MAP, texture);
    for (int face = 0; face < 6; ++face)
        glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, 0, GL_RGB16F, size, size, 0, GL_RGB,
                     GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(minFilter));
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    return texture;
}

// Draws the bound program into each face of `target`'s mip `level` (size x size).
void drawFaces(GLuint prog, GLuint target, int level, int size) {
    GLint faceLocation = glGetUniformLocation(prog, "uFace");
    glViewport(0, 0, size, size);
    for (int face = 0; face < 6; ++face) {
        glUniform1i(faceLocation, face);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                               GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, target, level);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            fail("cube face framebuffer incomplete");
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
}

class Stages {
public:
    Stages() : start_(Clock::now()), last_(start_) {}
    void end(const char* name) {
        glFinish();
        Clock::time_point now = Clock::now();
        std::printf("%-12s %.3f s\n", name, std::chrono::duration<double>(now - last_).count());
        last_ = now;
    }
    void total() const {
        std::printf("%-12s %.3f s\n", "total",
                    std::chrono::duration<double>(Clock::now() - start_).count());
    }

private:
    Clock::time_point start_, last_;
};

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s ENVIRONMENT.hdr\n", argv[0]);
        return 2;
    }
    Stages stages;

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
    if (!context) context = OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, nullptr);
    if (!context) fail("OSMesa could not create a context");
    // Everything is drawn into framebuffer objects; the default buffer only has to exist.
    unsigned char defaultBuffer[4 * 4 * 4];
    if (!OSMesaMakeCurrent(context, defaultBuffer, GL_UNSIGNED_BYTE, 4, 4))
        fail("OSMesaMakeCurrent failed");
    GLuint vertexArray = 0, framebuffer = 0;
    glGenVertexArrays(1, &vertexArray);
    glBindVertexArray(vertexArray);
    glGenFramebuffers(1, &framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    stages.end("context");

    stbi_set_flip_vertically_on_load(1);
    int width = 0, height = 0, channels = 0;
    float* data = stbi_loadf(argv[1], &width, &height, &channels, 0);
    if (!data) fail(std::string("cannot load ") + argv[1]);
    GLuint hdrTexture = 0;
    glGenTextures(1, &hdrTexture);
    glBindTexture(GL_TEXTURE_2D, hdrTexture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB16F, width, height, 0, channels == 4 ? GL_RGBA : GL_RGB,
                 GL_FLOAT, data);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    stbi_image_free(data);
    stages.end("load");

    GLuint environment = cubeTexture(kEnvironmentSize, GL_LINEAR_MIPMAP_LINEAR);
    GLuint equirectangular = program(kCubeVertexShader, kEquirectangularShader);
    glUseProgram(equirectangular);
    glUniform1i(glGetUniformLocation(equirectangular, "equirectangularMap"), 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, hdrTexture);
    drawFaces(equirectangular, environment, 0, kEnvironmentSize);
    // The prefilter samples these mips by solid angle (the lesson's fix for bright dots).
    glBindTexture(GL_TEXTURE_CUBE_MAP, environment);
    glGenerateMipmap(GL_TEXTURE_CUBE_MAP);
    stages.end("cube");

    GLuint irradianceMap = cubeTexture(kIrradianceSize, GL_LINEAR);
    GLuint irradiance = program(kCubeVertexShader, kIrradianceShader);
    glUseProgram(irradiance);
    glUniform1i(glGetUniformLocation(irradiance, "environmentMap"), 0);
    glBindTexture(GL_TEXTURE_CUBE_MAP, environment);
    drawFaces(irradiance, irradianceMap, 0, kIrradianceSize);
    stages.end("irradiance");

    GLuint prefilterMap = cubeTexture(kPrefilterSize, GL_LINEAR_MIPMAP_LINEAR);
    glGenerateMipmap(GL_TEXTURE_CUBE_MAP);  // allocates the mips the passes below fill
    const std::string version = "#version 330 core\n";
    GLuint prefilter = program(kCubeVertexShader, version + kImportanceSampling + kPrefilterShader);
    glUseProgram(prefilter);
    glUniform1i(glGetUniformLocation(prefilter, "environmentMap"), 0);
    glUniform1f(glGetUniformLocation(prefilter, "resolution"), float(kEnvironmentSize));
    glBindTexture(GL_TEXTURE_CUBE_MAP, environment);
    for (int mip = 0; mip < kPrefilterMips; ++mip) {
        glUniform1f(glGetUniformLocation(prefilter, "roughness"),
                    float(mip) / float(kPrefilterMips - 1));
        drawFaces(prefilter, prefilterMap, mip, kPrefilterSize >> mip);
    }
    stages.end("prefilter");

    GLuint lut = 0;
    glGenTextures(1, &lut);
    glBindTexture(GL_TEXTURE_2D, lut);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RG16F, kLutSize, kLutSize, 0, GL_RG, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    GLuint brdf = program(kLutVertexShader, version + kImportanceSampling + kLutShader);
    glUseProgram(brdf);
    glUniform1f(glGetUniformLocation(brdf, "resolution"), float(kLutSize));
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, lut, 0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        fail("lookup table framebuffer incomplete");
    glViewport(0, 0, kLutSize, kLutSize);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    stages.end("brdf_lut");

    if (glGetError() != GL_NO_ERROR) fail("GL error");
    stages.total();
    // One texel of the table, read after the total, shows the work was done: at its centre
    // (NdotV = roughness = 0.5) the split-sum scale and bias are 0.727 and 0.018 (the same
    // integral in double precision).
    float texel[2] = {};
    glReadPixels(kLutSize / 2, kLutSize / 2, 1, 1, GL_RG, GL_FLOAT, texel);
    std::printf("lut(0.5,0.5) %.4f %.4f\n", texel[0], texel[1]);
    OSMesaDestroyContext(context);
    return 0;
}
