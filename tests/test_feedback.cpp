// Feedback names the mistake from the shape of the error: each pattern, on synthetic values
// made from a reference by a known mistake (no GL: the classifier sees values only; the named
// terms are the built steps' own, from their libraries).
#include <gtest/gtest.h>

#include <cmath>

#include "grading/error_patterns.h"
#include "grading/input_fits.h"
#include "grading/term_fits.h"
#include "shader/code_facts.h"
#include "steps/plugin_host.h"

using namespace pbrlab;

namespace {

// A one-component step whose value is N.L-like, and a three-component one for colours.
ModuleDesc module(int components) {
    ModuleDesc d;
    d.id = "test";
    d.components = components;
    d.needs = NeedsAlbedo | NeedsRoughness | NeedsAo;
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.normal = r.direction();
        s.light = r.direction();
        s.view = r.around(s.normal, 0, 1);
        s.albedo = r.color();
        s.roughness = r.range(0.05, 1);
        s.ao = r.uniform();
        return s;
    };
    return d;
}

// Inputs where the reference is `truth` and the student's function is `student`.
template <class Truth, class Student>
FeedbackInputs inputs(const ModuleDesc& d, Truth truth, Student student) {
    FeedbackInputs in;
    in.module = &d;
    DomainRandom random(5);
    for (int i = 0; i < 400; ++i) {
        Surface s = d.domain(random);
        s.covered = true;
        const glm::dvec3 r = truth(s), v = student(s);
        in.surfaces.push_back(s);
        in.expected.push_back(r);
        in.values.push_back(v);
        in.slack.push_back(glm::max(glm::abs(r) * 1e-3, glm::dvec3(1e-6)));
    }
    return in;
}

double ndotl(const Surface& s) {
    return std::max(glm::dot(s.normal, s.light), 0.0);
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

}  // namespace

TEST(Feedback, ConstantFactorsAreNamed) {
    const ModuleDesc d = module(1);
    auto truth = [](const Surface& s) { return glm::dvec3(0.2 + ndotl(s)); };
    const std::string pi = classifyError(
        inputs(d, truth, [&](const Surface& s) { return truth(s) * 3.14159265358979; }));
    EXPECT_TRUE(contains(pi, "(= pi)") && contains(pi, "division by PI")) << pi;
    const std::string quarter = classifyError(
        inputs(d, truth, [&](const Surface& s) { return truth(s) * (3.14159265358979 / 4); }));
    EXPECT_TRUE(contains(quarter, "(= pi/4)")) << quarter;
    EXPECT_EQ(nameConstant(0.318309886), "1/pi");
    EXPECT_EQ(nameConstant(1.37), "");
}

TEST(Feedback, AStubIsRecognised) {
    const ModuleDesc d = module(1);
    const std::string s = classifyError(inputs(
        d, [](const Surface& s) { return glm::dvec3(ndotl(s)); },
        [](const Surface&) { return glm::dvec3(0); }));
    EXPECT_TRUE(contains(s, "returns 0 whatever the inputs") && contains(s, "stub")) << s;
}

TEST(Feedback, AConstantZeroFromAnEndlessLoopSaysSoNotStub) {
    // GLSL compilers delete a loop with no way out; the function's value is then 0 (Mesa).
    for (const char* loop :
         {"while (true) {}", "while(1){ x += 1.0; }", "for (;;) { x *= 2.0; }",
          "for (int i = 0; ; ++i) x += 1.0;", "do { x += 1.0; } while (true);"}) {
        const std::string code =
            std::string("float ndotl(vec3 N, vec3 L) {\n    float x = 0.0;\n    ") + loop +
            "\n    return max(dot(N, L), 0.0);\n}\n";
        const std::string why = whyAlwaysZero(code);
        EXPECT_TRUE(contains(why, "loop that never ends")) << loop << ": " << why;
        EXPECT_FALSE(contains(why, "stub")) << loop << ": " << why;
        // Through classifyError, as the grader calls it with the student's file.
        const ModuleDesc d = module(1);
        FeedbackInputs in = inputs(
            d, [](const Surface& s) { return glm::dvec3(ndotl(s)); },
            [](const Surface&) { return glm::dvec3(0); });
        in.studentCode = code;
        const std::string s = classifyError(in);
        EXPECT_TRUE(contains(s, "loop that never ends") && !contains(s, "stub")) << s;
    }
    // Loops that end, or a commented-out loop, are not endless; the stub is the stub.
    for (const char* code :
         {"while (true) { if (x > 1.0) break; x += 0.5; }", "for (;;) { return 0.0; }",
          "// while (true) {}\nreturn 0.0;", "/* for (;;) {} */ return 0.0;",
          "for (int i = 0; i < 4; ++i) x += 1.0;"})
        EXPECT_FALSE(contains(whyAlwaysZero(code), "never ends")) << code;
    EXPECT_TRUE(contains(whyAlwaysZero("// TODO: implement float ndotl(vec3 N, vec3 L)\n"
                                       "return 0.0;"),
                         "stub"));
    EXPECT_EQ(whyAlwaysZero("return 0.0 * dot(N, L);"), "");
}

TEST(Feedback, OffsetsPowersAndTermsAreNamed) {
    const ModuleDesc d = module(3);
    auto truth = [](const Surface& s) {
        return s.albedo * (0.1 + ndotl(s)) + 0.03 * s.albedo * s.ao;
    };
    const std::string offset = classifyError(
        inputs(d, truth, [&](const Surface& s) { return truth(s) + glm::dvec3(0.01); }));
    EXPECT_TRUE(contains(offset, "the reference + 0.01 everywhere")) << offset;
    const std::string ambient = classifyError(
        inputs(d, truth, [&](const Surface& s) { return truth(s) - 0.01 * s.albedo * s.ao; }));
    EXPECT_TRUE(contains(ambient, "0.01 x albedo x ao")) << ambient;
    auto unit = [](const Surface& s) { return 0.05 + 0.9 * s.albedo; };  // in (0, 1)
    const std::string power = classifyError(
        inputs(d, unit, [&](const Surface& s) { return glm::pow(unit(s), glm::dvec3(2.2)); }));
    EXPECT_TRUE(contains(power, "to the power 2.2")) << power;
}

TEST(Feedback, AnErrorConfinedToOneSideOfAnInputIsLocated) {
    const ModuleDesc d = module(1);
    // The clamp dropped: wrong exactly where N.L < 0.
    const std::string s = classifyError(inputs(
        d, [](const Surface& s) { return glm::dvec3(ndotl(s)); },
        [](const Surface& s) { return glm::dvec3(glm::dot(s.normal, s.light)); }));
    EXPECT_TRUE(contains(s, "wrong only where N.L < 0") && contains(s, "max(")) << "[" << s << "]";
}

TEST(Feedback, SwappedOrSingleWrongComponentsAreNamed) {
    const ModuleDesc d = module(3);
    auto truth = [](const Surface& s) { return s.albedo + glm::dvec3(0.1, 0.5, 0.9); };
    const std::string swapped = classifyError(inputs(d, truth, [&](const Surface& s) {
        const glm::dvec3 v = truth(s);
        return glm::dvec3(v.y, v.x, v.z);
    }));
    EXPECT_TRUE(contains(swapped, "components are swapped")) << swapped;
    const std::string one = classifyError(inputs(
        d, truth, [&](const Surface& s) { return truth(s) + glm::dvec3(0, 0, 2 * s.roughness); }));
    EXPECT_TRUE(contains(one, "third component")) << one;
}

TEST(Feedback, AnIgnoredArgumentIsFoundByVaryingOneInputAtATime) {
    const ModuleDesc d = module(3);
    auto truth = [](const Surface& s) { return s.albedo * (0.1 + ndotl(s)) * (0.5 + s.ao); };
    FeedbackInputs in = inputs(d, truth, [&](const Surface& s) {
        Surface t = s;
        t.ao = 0.5;  // ignores ao
        return truth(t);
    });
    in.domain = d.domain;
    in.reference = truth;
    in.student = [&](const std::vector<Surface>& surfaces) {
        std::vector<glm::dvec3> out;
        for (Surface s : surfaces) {
            s.ao = 0.5;
            out.push_back(truth(s));
        }
        return out;
    };
    const std::string s = classifyError(in);
    EXPECT_TRUE(contains(s, "does not change with ao")) << s;
}

TEST(Feedback, InputsAreDescribedByWhatTheDomainVaries) {
    const ModuleDesc d = module(1);
    Surface s;
    s.normal = {0, 0, 1};
    s.view = glm::normalize(glm::dvec3(0.6, 0, 0.8));
    s.light = {0, 0, 1};
    s.roughness = 0.25;
    s.ao = 0.5;
    const std::string text = describeInputs(d, s);
    EXPECT_TRUE(contains(text, "N.V 0.8") && contains(text, "roughness 0.25") &&
                contains(text, "ao 0.5"))
        << text;
    EXPECT_FALSE(contains(text, "metallic")) << text;  // the domain does not vary it
}

// Steps with named terms (term_fits.h): values made from the CPU reference by a known change.
namespace {

// The built steps, loaded once: their named terms are code in their libraries.
const ModuleRegistry& builtSteps() {
    static const ModuleRegistry registry{PBRLAB_MODULE_DIR};
    return registry;
}

// Inputs of step `id` over `domain`, with the context the term fits read.
template <class Truth, class Student>
FeedbackInputs stepInputs(ModuleDesc& d, const std::string& id, DomainFn domain,
                          const ReferenceContext& context, Truth truth, Student student) {
    d.id = id;
    d.namedTerms = builtSteps().find(id).desc->namedTerms;
    d.namedTermPoints = builtSteps().find(id).desc->namedTermPoints;
    d.components = 3;
    d.domain = std::move(domain);
    FeedbackInputs in = inputs(d, truth, student);
    in.context = &context;
    return in;
}

glm::dvec3 specular(const Surface& s) {
    return grazingBand(s) * ref::cookTorranceSpecular(s.normal, s.view, s.light,
                                                      ref::baseReflectivity(s.albedo, s.metallic),
                                                      s.roughness);
}

Surface radianceDomain(DomainRandom& r) {
    Surface s;
    s.position = {r.range(-1.5, 1.5), r.range(-1.5, 1.5), r.range(-1.5, 1.5)};
    s.lightPosition = s.position + r.direction() * r.logRange(0.05, 20);
    s.lightColor = r.color(100);
    return s;
}

}  // namespace

TEST(Feedback, AMissingOrDoubledTermIsNamed) {
    const ParamValues params;
    const ReferenceContext context{params, {}, glm::dvec3(0), nullptr};
    ModuleDesc d;
    const std::string noG = classifyError(
        stepInputs(d, "specular", highlightDomain, context, specular, [](const Surface& s) {
            return specular(s) / ref::geometrySmith(s.normal, s.view, s.light, s.roughness);
        }));
    EXPECT_TRUE(contains(noG, "divided by G:") && contains(noG, "geometry term G missing")) << noG;
    const std::string noNL = classifyError(stepInputs(
        d, "specular", highlightDomain, context, specular,
        [](const Surface& s) { return specular(s) * std::max(glm::dot(s.normal, s.light), 0.0); }));
    EXPECT_TRUE(contains(noNL, "times N.L") && contains(noNL, "N.L in the denominator")) << noNL;
}

TEST(Feedback, AnInputAtAnotherPowerIsNamed) {
    const ParamValues params;
    const ReferenceContext context{params, {}, glm::dvec3(0), nullptr};
    ModuleDesc d;
    auto radiance = [](const Surface& s) {
        return ref::pointLightRadiance(s.lightColor, s.lightPosition, s.position);
    };
    const std::string cube = classifyError(
        stepInputs(d, "radiance", radianceDomain, context, radiance, [](const Surface& s) {
            return s.lightColor / std::pow(glm::length(s.lightPosition - s.position), 3.0);
        }));
    EXPECT_TRUE(contains(cube, "1/d^3 where the reference has 1/d^2")) << cube;
    auto hdrDomain = [](DomainRandom& r) {
        Surface s;
        s.extra = {r.logRange(1e-3, 1e3), r.logRange(1e-3, 1e3), r.logRange(1e-3, 1e3), 1};
        return s;
    };
    auto encode = [](const Surface& s) { return ref::displayEncode(glm::dvec3(s.extra)); };
    const std::string gamma3 =
        classifyError(stepInputs(d, "tonemap", hdrDomain, context, encode, [](const Surface& s) {
            const glm::dvec3 h(s.extra);
            return glm::pow(h / (h + 1.0), glm::dvec3(1.0 / 3));
        }));
    EXPECT_TRUE(contains(gamma3, "gamma 3 (exponent 1/3) where the reference has gamma 2.2"))
        << gamma3;
}

TEST(Feedback, NoTermIsNamedWhenNoneExplainsTheError) {
    const ParamValues params;
    const ReferenceContext context{params, {}, glm::dvec3(0), nullptr};
    ModuleDesc d;
    // An error that follows no term: a ripple in roughness.
    const std::string ripple = nameTerm(stepInputs(
        d, "specular", highlightDomain, context, specular,
        [](const Surface& s) { return specular(s) * (1 + 0.3 * std::sin(20 * s.roughness)); }));
    EXPECT_EQ(ripple, "");
    // The reference itself: nothing to explain.
    EXPECT_EQ(nameTerm(stepInputs(d, "specular", highlightDomain, context, specular, specular)),
              "");
}

// Where an error lies is said by what the step's function receives (ModuleDesc::inputAxes), and
// what is said after it follows what the two functions do there.
namespace {

// ndf's shape: a function of N.H = N.H' (H = halfway(L, V)) and roughness, on inputs where V and
// L differ (as in the lesson's scenes).
ModuleDesc halfVectorStep() {
    ModuleDesc d;
    d.id = "test";
    d.components = 1;
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.normal = r.direction();
        s.view = r.direction();
        s.light = r.direction();
        s.roughness = r.range(0.05, 1);
        return s;
    };
    d.inputAxes = {
        {"N.H",
         [](const Surface& s) { return glm::dot(s.normal, ref::halfwayVector(s.light, s.view)); },
         nullptr},
        {"roughness", [](const Surface& s) { return s.roughness; }, nullptr}};
    return d;
}

glm::dvec3 ggx(const Surface& s) {
    return glm::dvec3(
        ref::distributionGGX(s.normal, ref::halfwayVector(s.light, s.view), s.roughness));
}

}  // namespace

TEST(Feedback, TheAxisIsWhatTheFunctionReceivesAndACutOffIsNotCalledAMissingGuard) {
    const ModuleDesc d = halfVectorStep();
    // D = 0 where N.H <= 0 (Walter et al.'s characteristic function): the reference is not 0
    // there, the student's is. Before: "wrong only where N.V < 0: is a max(..., 0.0) or a guard
    // for negative N.V missing?", the axis the function does not receive and the reverse of
    // what the code does.
    const std::string cut = classifyError(inputs(d, ggx, [](const Surface& s) {
        return glm::dot(s.normal, ref::halfwayVector(s.light, s.view)) <= 0 ? glm::dvec3(0)
                                                                            : ggx(s);
    }));
    EXPECT_TRUE(contains(cut, "wrong only where N.H < 0") &&
                contains(cut, "yours is 0 where N.H < 0, the reference is not"))
        << cut;
    EXPECT_FALSE(contains(cut, "missing") || contains(cut, "N.V")) << cut;
    DomainRandom random(1);
    EXPECT_EQ(describeInputs(d, d.domain(random)).rfind("N.H ", 0), 0u);
    // The clamp dropped (the student's varies where the reference is 0): the guard is missing.
    const ModuleDesc generic = module(1);
    const std::string noClamp = classifyError(inputs(
        generic, [](const Surface& s) { return glm::dvec3(ndotl(s)); },
        [](const Surface& s) { return glm::dvec3(glm::dot(s.normal, s.light)); }));
    EXPECT_TRUE(contains(noClamp, "guard for negative N.L missing")) << noClamp;
    // Both vary there (another formula on one side): no advice either way.
    const std::string other = classifyError(inputs(
        generic, [](const Surface& s) { return glm::dvec3(glm::dot(s.normal, s.light) + 1); },
        [](const Surface& s) {
            const double c = glm::dot(s.normal, s.light);
            return glm::dvec3(c > 0 ? c + 1 : 1 + 2 * c + 0.3 * c * c);
        }));
    EXPECT_TRUE(contains(other, "wrong only where N.L < 0")) << other;
    EXPECT_FALSE(contains(other, "missing?") || contains(other, "cut-off")) << other;
}

TEST(Feedback, ANaNIsTracedToTheCallThatMadeIt) {
    const ModuleDesc d = module(1);
    FeedbackInputs in = inputs(
        d, [](const Surface& s) { return glm::dvec3(ndotl(s)); },
        [](const Surface& s) { return glm::dvec3(s.roughness > 0.9 ? std::nan("") : ndotl(s)); });
    // The diagnosis build's answers (GL renders them in grading: tests/variants/brdf_lut has
    // the whole).
    auto answer = [&in](TraceSite site, bool confirmed, TraceSite other = {}) {
        in.traceNonFinite = [=](const std::vector<Surface>& points) {
            FeedbackInputs::NonFiniteOrigin origin;
            origin.site = site;
            origin.other = other;
            origin.traced = int(points.size());
            origin.points = site.traced() ? origin.traced : 0;
            origin.confirmed = confirmed;
            return origin;
        };
        return classifyError(in);
    };
    const std::string pow = answer({1, 14}, true);
    EXPECT_TRUE(contains(pow, "returns NaN at") &&
                contains(pow, "comes from pow with a negative base") &&
                contains(pow, "line 14 of test.glsl") && contains(pow, "guard or a clamp"))
        << pow;
    // Another call made one at those points too: both are said.
    const std::string two = answer({1, 14}, true, {2, 9});
    EXPECT_TRUE(contains(two,
                         "sqrt of a negative number, at line 9 of test.glsl makes one there "
                         "too"))
        << two;
    // pow of a positive base whose result overflows is not called a negative base.
    const std::string overflow = answer({-1, 14}, true);
    EXPECT_TRUE(contains(overflow, "comes from pow with a result too large for a float"))
        << overflow;
    EXPECT_FALSE(contains(overflow, "negative base")) << overflow;
    // A call that made one whose result the function drops (the value is NaN without it too) is
    // not called the cause, nor its guard missing.
    const std::string dropped = answer({2, 9}, false);
    EXPECT_TRUE(contains(dropped, "with its result replaced by 0 the value is still not finite") &&
                contains(dropped, "a division 0/0, Inf/Inf or 0 x Inf elsewhere?"))
        << dropped;
    EXPECT_FALSE(contains(dropped, "comes from") || contains(dropped, "guard")) << dropped;
    const std::string division = answer({}, false);
    EXPECT_TRUE(contains(division,
                         "No pow, sqrt, inversesqrt, log, log2, normalize, acos, asin or "
                         "mod in test.glsl made it from finite arguments there: a "
                         "division 0/0, Inf/Inf or 0 x Inf?"))
        << division;
}

// The diagnosis build's sites, as view_main.frag writes them (a float of call x 65536 + line,
// negative for the overflow case).
TEST(Feedback, TraceSitesAreReadAsWritten) {
    const TraceSite pow = traceSite(1 * 65536 + 31);
    EXPECT_EQ(pow.call, 1);
    EXPECT_EQ(pow.line, 31);
    EXPECT_EQ(pow.what(), "pow with a negative base (or 0 to a power <= 0)");
    const TraceSite overflow = traceSite(-(1 * 65536 + 7));
    EXPECT_EQ(overflow.call, -1);
    EXPECT_EQ(overflow.line, 7);
    EXPECT_EQ(overflow.what(), "pow with a result too large for a float (an overflow)");
    EXPECT_EQ(traceSite(0).traced(), nullptr);
    EXPECT_EQ(traceSite(std::nan("")).traced(), nullptr);
    EXPECT_EQ(traceSite(double(tracedCalls().size() + 1) * 65536).traced(), nullptr);
}

// The reference on other inputs (input_fits.h).
TEST(Feedback, AnInputUsedInAnothersPlaceIsNamed) {
    ModuleDesc d = module(1);
    d.reference = [](const Surface& s, const ReferenceContext&) { return glm::dvec3(ndotl(s)); };
    const ParamValues params;
    const ReferenceContext context{params, {}, glm::dvec3(0), nullptr};
    auto reference = [&](const Surface& s) { return d.reference(s, context); };
    FeedbackInputs flipped = inputs(d, reference, [](const Surface& s) {
        return glm::dvec3(std::max(glm::dot(s.normal, -s.light), 0.0));
    });
    flipped.context = &context;
    const std::string light = classifyError(flipped);
    EXPECT_TRUE(contains(light, "with -L in place of L")) << light;
    // Two inputs of the same range swapped; an input squared.
    ModuleDesc lut = module(1);
    lut.domain = [](DomainRandom& r) {
        Surface s;
        s.view = {std::sqrt(1 - 0.25), 0, 0.5};
        s.view = atCosine(s.normal, s.view, r.uniform());
        s.roughness = r.range(0.05, 1);
        return s;
    };
    auto f = [](double nv, double r) { return nv * nv * (1 - r) + 0.3 * r * r * r; };
    lut.reference = [f](const Surface& s, const ReferenceContext&) {
        return glm::dvec3(f(glm::dot(s.normal, s.view), s.roughness));
    };
    auto lutReference = [&](const Surface& s) { return lut.reference(s, context); };
    FeedbackInputs swapped = inputs(lut, lutReference, [f](const Surface& s) {
        return glm::dvec3(f(s.roughness, glm::dot(s.normal, s.view)));
    });
    swapped.context = &context;
    const std::string axes = classifyError(swapped);
    EXPECT_TRUE(contains(axes, "N.V and roughness swapped") &&
                contains(axes, "the two inputs used the wrong way round"))
        << axes;
    FeedbackInputs squared = inputs(lut, lutReference, [f](const Surface& s) {
        return glm::dvec3(f(glm::dot(s.normal, s.view), s.roughness * s.roughness));
    });
    squared.context = &context;
    const std::string square = classifyError(squared);
    EXPECT_TRUE(contains(square, "roughness^2 in place of roughness")) << square;
    // A change no input explains is not named by one.
    FeedbackInputs ripple = inputs(lut, lutReference, [f](const Surface& s) {
        return glm::dvec3(f(glm::dot(s.normal, s.view), s.roughness) *
                          (1 + 0.2 * std::sin(9 * s.roughness)));
    });
    ripple.context = &context;
    EXPECT_EQ(nameSubstitution(ripple), "");
}

TEST(Feedback, ADirectionAtAnotherLengthAndCurvesOfOneInputAreNamed) {
    ModuleDesc d = module(3);
    auto half = [](const Surface& s) { return ref::halfwayVector(s.light, s.view); };
    const std::string average =
        classifyError(inputs(d, half, [](const Surface& s) { return (s.light + s.view) * 0.5; }));
    EXPECT_TRUE(contains(average,
                         "Your value is (L + V) / 2, where the reference is "
                         "normalize(L + V)"))
        << average;
    // A wrap in N.L where the reference clamps it.
    const ModuleDesc one = module(1);
    const std::string wrap = classifyError(inputs(
        one, [](const Surface& s) { return glm::dvec3(ndotl(s)); },
        [](const Surface& s) { return glm::dvec3(0.5 + 0.5 * glm::dot(s.normal, s.light)); }));
    EXPECT_TRUE(contains(wrap, "Your value is 0.5 + 0.5 x N.L at every point")) << wrap;
    // A polynomial falloff where the reference has the inverse square.
    ModuleDesc light = module(3);
    light.domain = radianceDomain;
    const std::string falloff = classifyError(inputs(
        light,
        [](const Surface& s) {
            return ref::pointLightRadiance(s.lightColor, s.lightPosition, s.position);
        },
        [](const Surface& s) {
            const double x = glm::length(s.lightPosition - s.position);
            return s.lightColor / (1 + 0.09 * x + 0.032 * x * x);
        }));
    EXPECT_TRUE(contains(falloff, "the light's colour / (1 + 0.09 d + 0.032 d^2)")) << falloff;
}

TEST(Feedback, AColourTheSameAtEveryPointIsNoCurvesVariable) {
    // One albedo for every point, three different channels: three values, yet no variable. A
    // student's constant colour fits a three-parameter curve of it exactly, so a curve's
    // variable must take many values (input_fits.cpp, curveSamples).
    ModuleDesc d = module(3);
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.normal = r.direction();
        s.light = r.around(s.normal, 0.1, 1);
        s.view = r.around(s.normal, 0, 1);
        s.albedo = {0.9, 0.5, 0.2};
        s.roughness = r.range(0.05, 1);
        return s;
    };
    const std::string curve = nameCurve(inputs(
        d, [](const Surface& s) { return s.albedo * ndotl(s); },
        [](const Surface&) { return glm::dvec3(0.3, 0.25, 0.4); }));
    EXPECT_FALSE(contains(curve, "albedo")) << curve;
}
