#include "grading/mutants_semantic.h"

#include <algorithm>
#include <cstdio>
#include <set>

#include "grading/mutants_helper.h"
#include "grading/step_grader.h"
#include "render/renderer.h"
#include "util/error.h"

namespace pbrlab {

namespace {

// The significant tokens of a file (no spaces, comments or preprocessor lines), with the
// bracket matching the families need.
class Code {
public:
    explicit Code(const std::string& source) : source_(source) {
        for (const GlslToken& t : tokenizeGlsl(source))
            if (t.kind == GlslToken::Identifier || t.kind == GlslToken::Number ||
                t.kind == GlslToken::Operator)
                tokens_.push_back(t);
    }
    size_t size() const { return tokens_.size(); }
    const GlslToken& operator[](size_t k) const { return tokens_[k]; }
    bool is(size_t k, const char* text) const { return k < size() && tokens_[k].text == text; }
    bool identifier(size_t k) const {
        return k < size() && tokens_[k].kind == GlslToken::Identifier;
    }
    // The token that closes the bracket opened at k (size() when unbalanced).
    size_t closing(size_t open) const {
        int depth = 0;
        for (size_t k = open; k < size(); ++k) {
            const std::string& t = tokens_[k].text;
            depth += (t == "(" || t == "[" || t == "{") - (t == ")" || t == "]" || t == "}");
            if (depth == 0) return k;
        }
        return size();
    }
    // Where tokens [b, e] begin and end in the file.
    size_t begin(size_t k) const { return tokens_[k].offset; }
    size_t end(size_t k) const { return tokens_[k].offset + tokens_[k].text.size(); }
    std::string text(size_t b, size_t e) const {
        return source_.substr(begin(b), end(e) - begin(b));
    }
    const std::string& source() const { return source_; }

    // The top-level arguments of the call whose "(" is at `open`: [first, last] token pairs.
    std::vector<std::pair<size_t, size_t>> arguments(size_t open) const {
        std::vector<std::pair<size_t, size_t>> out;
        const size_t close = closing(open);
        size_t start = open + 1;
        int depth = 0;
        for (size_t k = open + 1; k <= close && k < size(); ++k) {
            const std::string& t = tokens_[k].text;
            if (k == close || (depth == 0 && t == ",")) {
                if (k > start) out.push_back({start, k - 1});
                start = k + 1;
                continue;
            }
            depth += (t == "(" || t == "[") - (t == ")" || t == "]");
        }
        return out;
    }

    struct Function {
        size_t bodyOpen, bodyClose;                               // "{" and "}"
        std::vector<std::pair<std::string, std::string>> params;  // type, name
    };
    // Every function defined in the file.
    std::vector<Function> functions() const {
        std::vector<Function> out;
        for (size_t k = 0; k + 2 < size(); ++k) {
            if (!identifier(k) || !identifier(k + 1) || !is(k + 2, "(")) continue;
            const size_t close = closing(k + 2);
            if (!is(close + 1, "{")) continue;
            Function f{close + 1, closing(close + 1), {}};
            for (const auto& [b, e] : arguments(k + 2))
                if (e > b && identifier(e) && identifier(e - 1))
                    f.params.push_back({tokens_[e - 1].text, tokens_[e].text});
            out.push_back(f);
        }
        return out;
    }

private:
    const std::string& source_;
    std::vector<GlslToken> tokens_;
};

std::string floatLiteral(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    std::string s = buf;
    if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
    return s;
}

const std::set<std::string>& textureReads() {
    static const std::set<std::string> names = {"texture",         "textureLod",  "textureGrad",
                                                "texelFetch",      "textureProj", "textureOffset",
                                                "textureLodOffset"};
    return names;
}

// --- radiance: a nonlinearity on every texture read -------------------------------------------

// Each read (the call and its swizzle) as a clamp at 10 (above the soft sky's brightest texel,
// about 8, which grading judges estimators on) and at 1000 (below a real sun, 20000 in the
// shipped sky), a tone curve, a power, and an offset (affine: wrong on scaled or summed
// environments). The witness: the environment scaled by 1e-3 and 1e3, where each of them
// differs from a linear read.
std::vector<Mutant> nonlinearReads(const SemanticContext& c) {
    const Code code(c.solution);
    std::vector<Mutant> out;
    for (size_t k = 0; k + 1 < code.size(); ++k) {
        if (!textureReads().count(code[k].text) || !code.is(k + 1, "(")) continue;
        if (k > 0 && code.is(k - 1, ".")) continue;
        size_t last = code.closing(k + 1);
        if (last >= code.size()) continue;
        int components = 4;
        if (code.is(last + 1, ".") && code.identifier(last + 2)) {
            components = int(code[last + 2].text.size());
            last += 2;
        }
        const std::string type = components == 1 ? "float" : "vec" + std::to_string(components);
        const std::string x = code.text(k, last);
        auto constant = [&](double v) {
            return components == 1 ? floatLiteral(v) : type + "(" + floatLiteral(v) + ")";
        };
        const std::string forms[] = {
            "min(" + x + ", " + constant(10) + ")", "min(" + x + ", " + constant(1000) + ")",
            "(" + x + " / (1.0 + " + x + "))",      "pow(" + x + ", " + constant(0.9) + ")",
            "(" + x + " + " + constant(0.01) + ")",
        };
        for (const std::string& form : forms) {
            Mutant m =
                mutantFromEdits("radiance", c.solution, {{code.begin(k), code.end(last), form}});
            m.witness.environmentScales = {1e-3, 1e3};
            out.push_back(std::move(m));
        }
    }
    return out;
}

// --- count: a cap on every count --------------------------------------------------------------

// Every integer parameter of every function, capped at 512, 2048 and 16384 wherever the body
// reads it: above 512 the largest count graded today was 1024; 2048 and 16384 lie above it.
// The witness: the step's count parameters at twice the cap.
std::vector<Mutant> cappedCounts(const SemanticContext& c) {
    const Code code(c.solution);
    std::vector<Mutant> out;
    for (const Code::Function& f : code.functions())
        for (const auto& [type, name] : f.params) {
            if (type != "uint" && type != "int") continue;
            for (int cap : {512, 2048, 16384}) {
                const std::string bound = std::to_string(cap) + (type == "uint" ? "u" : "");
                std::vector<TextEdit> edits;
                for (size_t k = f.bodyOpen; k < f.bodyClose; ++k)
                    if (code[k].text == name && !code.is(k - 1, "."))
                        edits.push_back(
                            {code.begin(k), code.end(k), "min(" + name + ", " + bound + ")"});
                if (edits.empty()) continue;
                Mutant m = mutantFromEdits("count", c.solution, edits);
                m.witness.counts = {2 * cap};
                out.push_back(std::move(m));
            }
        }
    return out;
}

// --- bits: fewer bits in every bit operation --------------------------------------------------

// bitfieldReverse keeping 16 or 24 of the 32 reversed bits (a radical inverse of 16 or 24
// bits: the same for i < 2^16 or 2^24), a mask narrowed to its low 16 (or 8) bits, a shift by
// a constant 8 bits further. No step's view reaches the indices where they differ (the
// Hammersley view stops at n = 1024), so the witness is by construction.
std::vector<Mutant> fewerBits(const SemanticContext& c) {
    const Code code(c.solution);
    std::vector<Mutant> out;
    auto add = [&](std::vector<TextEdit> edits, const std::string& where) {
        Mutant m = mutantFromEdits("bits", c.solution, std::move(edits));
        m.witness.byConstruction = where;
        out.push_back(std::move(m));
    };
    for (size_t k = 0; k + 1 < code.size(); ++k) {
        const std::string& t = code[k].text;
        if (t == "bitfieldReverse" && code.is(k + 1, "(")) {
            const size_t close = code.closing(k + 1);
            if (close >= code.size()) continue;
            const std::string call = code.text(k, close);
            add({{code.begin(k), code.end(close), "(" + call + " & 0xFFFF0000u)"}},
                "a bit reversal of 16 bits: differs for arguments >= 2^16");
            add({{code.begin(k), code.end(close), "(" + call + " & 0xFFFFFF00u)"}},
                "a bit reversal of 24 bits: differs for arguments >= 2^24");
        } else if (code[k].kind == GlslToken::Number && t.rfind("0x", 0) == 0) {
            const unsigned long mask = std::strtoul(t.c_str(), nullptr, 16);
            const unsigned long narrowed = mask > 0xFFFF ? mask & 0xFFFF : mask & 0xFF;
            if (narrowed == mask) continue;
            char buf[24];
            std::snprintf(buf, sizeof buf, "0x%lX", narrowed);
            std::string suffix;
            for (size_t s = t.size(); s > 0 && std::strchr("uU", t[s - 1]); --s) suffix = "u";
            add({{code.begin(k), code.end(k), buf + suffix}},
                "a mask narrowed to " + std::string(mask > 0xFFFF ? "16" : "8") +
                    " bits: differs for values with a higher bit set");
        } else if ((t == "<<" || t == ">>" || t == "<<=" || t == ">>=") &&
                   code[k + 1].kind == GlslToken::Number) {
            std::string amount = code[k + 1].text, suffix;
            while (!amount.empty() && std::strchr("uU", amount.back()))
                suffix = "u", amount.pop_back();
            const long n = std::strtol(amount.c_str(), nullptr, 0);
            const long changed = n + 8 < 32 ? n + 8 : n - 8;
            add({{code.begin(k + 1), code.end(k + 1), std::to_string(changed) + suffix}},
                "a shift by " + std::to_string(changed) + " for " + std::to_string(n) +
                    ": differs for values with a bit set in the 8 bits it now drops");
        }
    }
    return out;
}

// --- host: every host-provided value replaced by its value today ------------------------------

// The scene grading draws the step in by default, with the environment it judges the step on.
Scene gradedScene(const SemanticContext& c) {
    const ModuleDesc& d = *c.module.desc;
    Scene scene = loadScene(c.paths.scene(d.scene));
    if (d.estimator && !d.estimator->environment.empty())
        scene.environment = d.estimator->environment;
    return scene;
}

std::string vec3Literal(const glm::dvec3& v) {
    return "vec3(" + floatLiteral(v.x) + ", " + floatLiteral(v.y) + ", " + floatLiteral(v.z) + ")";
}

// NUM_LIGHTS, the light arrays, uPrefilterMaxLod and textureSize of a contract sampler (at a
// constant LOD), each written as the constant the host binds in grading today (the step's
// scene, the default maps). The witness: the scene with another light count, other positions
// and colours; the maps at other sizes and mip counts (--error-budget builds maps of other
// sizes; IblSettings allows other mip counts, which the contract's uPrefilterMaxLod follows).
std::vector<Mutant> hostValues(const SemanticContext& c) {
    const Code code(c.solution);
    const Scene scene = gradedScene(c);
    // What a sampler's size depends on, and sizes the host also builds it at (one smaller,
    // one larger than grading's: a quadrature whose nodes halve a finer mip's texels reads
    // exactly the coarser box-filtered mip, so one size alone can hide the constant).
    struct Sampler {
        const char* name;
        const char* setting;  // the IblSettings field of its size
        int smaller, larger;
    };
    static const Sampler samplers[] = {{"uEnvironment", "environmentSize", 128, 512},
                                       {"uIrradianceMap", "irradianceSize", 16, 64},
                                       {"uPrefilterMap", "prefilterSize", 64, 256},
                                       {"uBrdfLut", "lutWidth", 512, 2048}};
    const IblSettings& ibl = step_grading::kGradingIbl;
    auto sizeToday = [&](const std::string& sampler) -> glm::ivec2 {
        const bool derived = sampler != "uEnvironment";
        const IblInputs& maps = c.renderer.environmentInputs(scene, ibl, derived);
        if (sampler == "uEnvironment") return glm::ivec2(maps.environment.size());
        if (sampler == "uIrradianceMap") return glm::ivec2(maps.irradiance.size());
        if (sampler == "uPrefilterMap") return glm::ivec2(maps.prefilter.size());
        return {maps.lut.width, maps.lut.height};
    };
    std::vector<Mutant> out;
    for (size_t k = 0; k < code.size(); ++k) {
        const std::string& t = code[k].text;
        if (!code.identifier(k) || code.is(k - 1, ".")) continue;
        if (t == "NUM_LIGHTS") {
            Mutant m =
                mutantFromEdits("host", c.solution,
                                {{code.begin(k), code.end(k),
                                  std::to_string(std::max<size_t>(scene.lights.size(), 1))}});
            m.witness.otherLights = true;
            out.push_back(std::move(m));
        } else if ((t == "uLightPositions" || t == "uLightColors") && code.is(k + 1, "[") &&
                   !scene.lights.empty()) {
            std::string array = "vec3[" + std::to_string(scene.lights.size()) + "](";
            for (size_t i = 0; i < scene.lights.size(); ++i)
                array +=
                    (i ? ", " : "") + vec3Literal(t == "uLightPositions" ? scene.lights[i].position
                                                                         : scene.lights[i].color);
            Mutant m =
                mutantFromEdits("host", c.solution, {{code.begin(k), code.end(k), array + ")"}});
            m.witness.otherLights = true;
            out.push_back(std::move(m));
        } else if (t == "uPrefilterMaxLod") {
            const double lod = c.renderer.environmentInputs(scene, ibl, true).prefilterMaxLod;
            Mutant m = mutantFromEdits("host", c.solution,
                                       {{code.begin(k), code.end(k), floatLiteral(lod)}});
            m.witness.ibl = {{"prefilterMips", ibl.prefilterMips - 1},
                             {"prefilterMips", ibl.prefilterMips + 1}};
            out.push_back(std::move(m));
        } else if (t == "textureSize" && code.is(k + 1, "(")) {
            const auto args = code.arguments(k + 1);
            if (args.size() != 2 || args[0].first != args[0].second ||
                args[1].first != args[1].second || code[args[1].first].kind != GlslToken::Number)
                continue;
            const Sampler* s = nullptr;
            for (const Sampler& x : samplers)
                if (code[args[0].first].text == x.name) s = &x;
            if (!s) continue;
            const int lod = std::atoi(code[args[1].first].text.c_str());
            const glm::ivec2 size = glm::max(sizeToday(s->name) >> lod, glm::ivec2(1));
            Mutant m = mutantFromEdits(
                "host", c.solution,
                {{code.begin(k), code.end(code.closing(k + 1)),
                  "ivec2(" + std::to_string(size.x) + ", " + std::to_string(size.y) + ")"}});
            m.witness.ibl = {{s->setting, s->smaller}, {s->setting, s->larger}};
            out.push_back(std::move(m));
        }
    }
    return out;
}

}  // namespace

const std::vector<SemanticFamily>& semanticFamilies() {
    static const std::vector<SemanticFamily> f = {
        {"radiance",
         "every texture read clamped at 10 and at 1000, tone-mapped x / (1 + x), raised to 0.9, "
         "offset by 0.01",
         "nonlinear in radiance", nullptr, nonlinearReads},
        {"count", "every integer parameter capped at 512, 2048, 16384 where it is read",
         "ignores its count above the cap", nullptr, cappedCounts},
        {"bits",
         "bitfieldReverse keeping 16 or 24 bits, a mask narrowed to 16 (8) bits, a constant "
         "shift 8 bits further",
         "uses fewer bits than its inputs have", nullptr, fewerBits},
        {"host",
         "NUM_LIGHTS, the light arrays, uPrefilterMaxLod, textureSize(...) replaced by the "
         "value the host gives them in grading today",
         "hard-coded host value", nullptr, hostValues},
        {"helper", "every visible helper that computes the step, called",
         "calls a helper that computes the step",
         "it calls code that computes the step: its values are the step's by construction",
         [](const SemanticContext& c) { return helperCallMutants(c.renderer, c.module); }},
    };
    return f;
}

const SemanticFamily* semanticFamily(const std::string& name) {
    for (const SemanticFamily& f : semanticFamilies())
        if (name == f.name) return &f;
    return nullptr;
}

std::vector<Mutant> generateSemanticMutants(const SemanticContext& context) {
    std::vector<Mutant> out;
    std::set<std::string> seen{context.solution};
    for (const SemanticFamily& f : semanticFamilies())
        for (Mutant& m : f.generate(context))
            if (seen.insert(m.text).second) out.push_back(std::move(m));
    return out;
}

nlohmann::json mutantsToJson(const std::vector<Mutant>& mutants) {
    nlohmann::json out = nlohmann::json::array();
    for (const Mutant& m : mutants) {
        const Witness& w = m.witness;
        out.push_back({{"family", m.family},
                       {"description", m.description},
                       {"change", m.change},
                       {"line", m.line},
                       {"text", m.text},
                       {"witness",
                        {{"environment_scales", w.environmentScales},
                         {"counts", w.counts},
                         {"ibl", w.ibl},
                         {"other_lights", w.otherLights},
                         {"by_construction", w.byConstruction}}}});
    }
    return out;
}

std::vector<Mutant> mutantsFromJson(const nlohmann::json& j) {
    std::vector<Mutant> out;
    for (const nlohmann::json& x : j) {
        Mutant m;
        m.family = x.at("family");
        m.description = x.at("description");
        m.change = x.at("change");
        m.line = x.at("line");
        m.text = x.at("text");
        const nlohmann::json& w = x.at("witness");
        m.witness.environmentScales = w.at("environment_scales").get<std::vector<double>>();
        m.witness.counts = w.at("counts").get<std::vector<int>>();
        m.witness.ibl = w.at("ibl").get<std::vector<std::pair<std::string, int>>>();
        m.witness.otherLights = w.at("other_lights");
        m.witness.byConstruction = w.at("by_construction");
        out.push_back(std::move(m));
    }
    return out;
}

}  // namespace pbrlab
