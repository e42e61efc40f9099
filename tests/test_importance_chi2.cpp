// Step 16 on the GPU, judged as a sampler: a chi-square test of the half vectors that a
// student's importanceSampleGGX (or the reference solution) returns, against the GGX density
// D(h) (N.h) per steradian. The per-pixel check (`pbrlab check importance`) compares what
// every correct frame shares (N.H and the balance of phi around N); this test compares the
// distribution itself, so a correct sampler in any orthonormal frame around N passes and a
// lobe of the wrong shape (alpha where alpha^2 belongs, ...) fails, as DESIGN.md asks.
//
// The student function runs in the module's stepwise program, with a view of this test's own
// that returns H (labs/16-importance/view.glsl shows frame-free quantities instead). Bins are
// measured in the test's own frame around N: (log tan theta_h, phi).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "gl/context.h"
#include "pbrlab/ibl_reference.h"
#include "renderer.h"
#include "test_support.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

constexpr int kThetaBins = 16, kPhiBins = 8;
constexpr int kSide = 128;  // Xi per case: kSide^2 = 16384, 128 expected per cell
constexpr double kFamilySignificance = 0.01;

// Integral of f over [a, b]: 8-point Gauss-Legendre on `panels` equal panels.
template <class F>
double integrate(const F& f, double a, double b, int panels) {
    static const double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                0.9602898564975363};
    static const double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                0.1012285362903763};
    double sum = 0;
    const double h = (b - a) / panels;
    for (int p = 0; p < panels; ++p) {
        const double mid = a + (p + 0.5) * h, half = 0.5 * h;
        for (int k = 0; k < 4; ++k)
            sum += w[k] * half * (f(mid - half * x[k]) + f(mid + half * x[k]));
    }
    return sum;
}

// Theta is binned by s = ln tan(theta), where the GGX lobe is a smooth bump around ln(alpha)
// for every roughness and float directions keep their relative precision. The bins are
// defined by the closed-form quantiles (so they are about equally full); their expected
// probabilities do not trust that: they are integrals of the density, 2 pi D cos sin dtheta
// = 2 pi D cos^2 sin^2 ds, and the test asserts that they add up to 1.
struct ThetaBins {
    std::vector<double> edges;        // in s, kThetaBins + 1
    std::vector<double> probability;  // per bin
};

ThetaBins thetaBins(double roughness) {
    const double alpha = roughness * roughness, lnAlpha = std::log(alpha);
    ThetaBins bins;
    for (int j = 0; j <= kThetaBins; ++j) {
        const double u = double(j) / kThetaBins;
        bins.edges.push_back(j == 0            ? lnAlpha - 40
                             : j == kThetaBins ? lnAlpha + 40
                                               : lnAlpha + 0.5 * std::log(u / (1 - u)));
    }
    auto density = [&](double s) {
        const double theta = std::atan(std::exp(s)), c = std::cos(theta), sn = std::sin(theta);
        return 2 * ref::kPi * ref::pdfGGXHalfVector(c, roughness) * sn * c * sn;
    };
    for (int j = 0; j < kThetaBins; ++j)
        bins.probability.push_back(integrate(density, bins.edges[size_t(j)],
                                             bins.edges[size_t(j) + 1],
                                             j == 0 || j == kThetaBins - 1 ? 512 : 64));
    return bins;
}

// An orthonormal frame around N of the test's own (Gram-Schmidt on the axis least aligned
// with N): a student's frame is a rotation or reflection of it, which leaves a uniform phi
// uniform.
void testFrame(const glm::dvec3& N, glm::dvec3& T, glm::dvec3& B) {
    const glm::dvec3 a = std::abs(N.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    T = glm::normalize(a - N * glm::dot(N, a));
    B = glm::cross(N, T);
}

struct Case {
    glm::dvec3 normal;
    double roughness;
};

// +z and -z (the seed's frame switches its up vector there), a normal inside and one at the
// edge of that switch-over cone, the axes x and y, and two tilted normals.
std::vector<Case> cases() {
    const glm::dvec3 normals[] = {{0, 0, 1}, {0, 0, -1}, {0.02, 0.03, 1},  {0.0447, 0, 1},
                                  {1, 0, 0}, {0, 1, 0},  {0.3, -0.5, 0.8}, {-0.6, 0.2, -0.75}};
    std::vector<Case> c;
    for (const auto& n : normals)
        for (double r : {0.1, 0.3, 0.6, 1.0}) c.push_back({glm::normalize(n), r});
    return c;
}

struct Outcome {
    double pValue = 1;
    int invalid = 0;  // non-finite, not unit length (|1 - |H|| > 1e-3) or N.H <= 0
};

struct Session {
    std::unique_ptr<GlContext> context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR, paths.labs()};
    LabRenderer renderer{paths};
    test::TempDir viewDir;
    LoadedModule sampler;  // the importance module with a view that returns H

    Session() {
        sampler = modules.find("importance");
        viewDir.write("view.glsl",
                      "// The chi-square test's view: the sampled half vector itself.\n"
                      "vec3 view(Surface s)\n{\n"
                      "    return importanceSampleGGX(s.extra.xy, s.normal, s.roughness);\n}\n");
        sampler.sourceDir = viewDir.path;
    }

    Outcome run(const Case& c, const StudentSource& source, std::uint64_t seed) {
        std::mt19937_64 rng(seed);
        // Uniform in [0, 1) with 24 bits: exact in the float textures (never rounds up to 1).
        auto uniform = [&rng] { return double(rng() >> 40) * (1.0 / 16777216.0); };
        std::vector<Surface> surfaces(size_t(kSide) * kSide);
        for (Surface& s : surfaces) {
            s.covered = true;
            s.normal = glm::dvec3(glm::vec3(c.normal));  // what the GPU receives
            s.roughness = c.roughness;
            s.extra = {uniform(), uniform(), 0, 0};
        }
        const ModuleDesc& d = *sampler.desc;
        Scene scene = loadScene(paths.scene(d.scene));
        RenderResult r = renderer.renderSurfaces(sampler, ParamValues(d.params), scene, source,
                                                 surfaces, kSide, kSide);
        const ThetaBins bins = thetaBins(c.roughness);
        double total = 0;
        for (double p : bins.probability) total += p;
        EXPECT_NEAR(total, 1.0, 1e-6) << "the GGX density does not integrate to 1";
        glm::dvec3 T, B;
        const glm::dvec3 N = glm::normalize(glm::dvec3(glm::vec3(c.normal)));
        testFrame(N, T, B);
        std::vector<double> observed(size_t(kThetaBins) * kPhiBins, 0);
        Outcome out;
        int valid = 0;
        for (size_t i = 0; i < surfaces.size(); ++i) {
            const glm::dvec3 H(r.value.pixels[i * 4], r.value.pixels[i * 4 + 1],
                               r.value.pixels[i * 4 + 2]);
            const double cosTheta = glm::dot(N, H);
            if (!std::isfinite(H.x + H.y + H.z) || std::abs(glm::length(H) - 1) > 1e-3 ||
                cosTheta <= 0) {
                ++out.invalid;
                continue;
            }
            ++valid;
            const double s = std::log(glm::length(glm::cross(N, H)) / cosTheta);
            const int tb =
                std::clamp(int(std::upper_bound(bins.edges.begin(), bins.edges.end(), s) -
                               bins.edges.begin()) -
                               1,
                           0, kThetaBins - 1);
            double phi = std::atan2(glm::dot(H, B), glm::dot(H, T));
            if (phi < 0) phi += 2 * ref::kPi;
            const int pb = std::min(int(phi / (2 * ref::kPi) * kPhiBins), kPhiBins - 1);
            observed[size_t(tb * kPhiBins + pb)] += 1;
        }
        double chi2 = 0;
        for (int j = 0; j < kThetaBins; ++j)
            for (int k = 0; k < kPhiBins; ++k) {
                const double e = bins.probability[size_t(j)] / kPhiBins * valid;
                const double o = observed[size_t(j * kPhiBins + k)];
                chi2 += (o - e) * (o - e) / e;
            }
        out.pValue = valid > 0 ? test::gammaQ((kThetaBins * kPhiBins - 1) / 2.0, chi2 / 2) : 0;
        return out;
    }
};

struct Sampler {
    std::string file;  // tests/variants/importance/<file>, or empty: the reference solution
};
void PrintTo(const Sampler& s, std::ostream* os) {
    *os << (s.file.empty() ? "reference solution" : s.file);
}

fs::path variantDir() {
    return fs::path(PBRLAB_SOURCE_DIR) / "tests" / "variants" / "importance";
}

std::vector<Sampler> samplers() {
    std::vector<Sampler> v{{""}};
    if (fs::exists(variantDir()))
        for (const auto& f : fs::directory_iterator(variantDir()))
            if (f.path().extension() == ".glsl") v.push_back({f.path().filename().string()});
    std::sort(v.begin(), v.end(),
              [](const Sampler& a, const Sampler& b) { return a.file < b.file; });
    return v;
}

class ImportanceChiSquare : public testing::TestWithParam<Sampler> {};

}  // namespace

// Significance 0.01 for the family of cases (Sidak: 1 - 0.99^(1/cases) per case), with fixed
// seeds, so a correct sampler fails with probability 0.01 overall. Correct samplers must pass
// every case; a mistake must be rejected in at least one (alpha for alpha^2 is invisible at
// roughness 1, a tangent-space H at N = +z), or return a sample that is not a unit vector
// above the surface.
TEST_P(ImportanceChiSquare, CorrectSamplersFollowTheGgxDensityMistakesDoNot) {
    const Sampler& sampler = GetParam();
    Session session;
    test::TempDir kit;
    StudentSource source;
    if (!sampler.file.empty()) {
        fs::copy(variantDir() / sampler.file, kit.path / "importance.glsl");
        source.dir = kit.path;
    }
    const std::vector<Case> all = cases();
    const double perCase = 1 - std::pow(1 - kFamilySignificance, 1.0 / double(all.size()));
    const bool correct = sampler.file.rfind("mistake_", 0) != 0;
    int rejected = 0;
    double smallest = 1;
    std::ostringstream log;
    std::uint64_t seed = 2024;
    for (const Case& c : all) {
        const Outcome o = session.run(c, source, seed++);
        const bool reject = o.invalid > 0 || o.pValue < perCase;
        rejected += reject;
        smallest = std::min(smallest, o.pValue);
        log << "  N (" << c.normal.x << ", " << c.normal.y << ", " << c.normal.z << ") roughness "
            << c.roughness << ": p = " << o.pValue << ", invalid " << o.invalid
            << (reject ? "  REJECTED" : "") << "\n";
        if (correct) {
            EXPECT_FALSE(reject) << "N (" << c.normal.x << ", " << c.normal.y << ", " << c.normal.z
                                 << ") roughness " << c.roughness << ": p = " << o.pValue
                                 << ", invalid samples " << o.invalid;
        }
    }
    std::printf(
        "[ measured ] %s: smallest p %.3g over %zu cases (per-case significance %.3g), "
        "%d rejected\n",
        sampler.file.empty() ? "reference solution" : sampler.file.c_str(), smallest, all.size(),
        perCase, rejected);
    if (!correct) {
        EXPECT_GT(rejected, 0) << "a mistake passed every case:\n" << log.str();
    }
}

INSTANTIATE_TEST_SUITE_P(Labs, ImportanceChiSquare, testing::ValuesIn(samplers()),
                         [](const testing::TestParamInfo<Sampler>& info) {
                             std::string name =
                                 info.param.file.empty()
                                     ? std::string("reference_solution")
                                     : info.param.file.substr(0, info.param.file.size() - 5);
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });
