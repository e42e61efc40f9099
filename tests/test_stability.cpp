// Every reference solution stays finite (and non-negative where the quantity is) on the
// extreme inputs, on the GPU and in the CPU reference.
#include <gtest/gtest.h>

#include "gl/context.h"
#include "grading/stability.h"
#include "render/evaluate.h"
#include "test_support.h"

using namespace pbrlab;

TEST(Stability, EveryReferenceIsFiniteOnTheExtremeSet) {
    auto context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    LabRenderer renderer{paths};
    ASSERT_FALSE(modules.modules().empty());
    for (const auto& m : modules.modules()) {
        Scene scene = loadScene(paths.scene(m.desc->scene));
        StabilityResult r = stabilitySweep(renderer, m, scene);
        EXPECT_EQ(r.referenceNonFinite, 0) << m.desc->id << ": " << r.firstProblem;
        EXPECT_EQ(r.referenceNegative, 0) << m.desc->id << ": " << r.firstProblem;
        EXPECT_EQ(r.gpu.nonFinite(), 0) << m.desc->id << ": " << r.firstProblem;
        if (m.desc->nonNegative) {
            EXPECT_EQ(r.gpu.negativeCount, 0) << m.desc->id << ": " << r.firstProblem;
        }
    }
}

TEST(Stability, ExtremeSetCoversTheDesignsEdges) {
    ExtremeSet set = extremeSurfaces();
    bool roughness0 = false, vIsMinusL = false, lightOnPoint = false, bigLight = false,
         grazing = false;
    for (size_t i = 0; i < set.labels.size(); ++i) {
        const Surface& s = set.surfaces[i];
        roughness0 = roughness0 || s.roughness == 0;
        vIsMinusL =
            vIsMinusL || (glm::length(s.view + s.light) < 1e-12 && glm::length(s.light) > 0);
        lightOnPoint = lightOnPoint || s.lightPosition == s.position;
        bigLight = bigLight || s.lightColor.x >= 1e6;
        grazing = grazing || glm::dot(s.normal, s.view) == 0;
    }
    EXPECT_TRUE(roughness0 && vIsMinusL && lightOnPoint && bigLight && grazing);
}

TEST(Stability, SceneLightsAreSweptForViewsThatReadThem) {
    // reflectance reads the scene's lights (uniforms), not the extreme set's per-surface
    // light: only the second pass, with the scene's lights at the extremes, reaches a light
    // sitting on the shaded point. A student's own unguarded inverse square is Inf there,
    // and Inf times a zero cosine is NaN.
    auto context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    LabRenderer renderer{paths};
    const LoadedModule& reflectance = modules.find("reflectance");
    EXPECT_TRUE(readsSceneLights(renderer, reflectance, {}, 1));
    EXPECT_FALSE(readsSceneLights(renderer, modules.find("ndotl"), {}, 1));
    test::TempDir kit;
    kit.write("reflectance.glsl", R"(
vec3 reflectedRadiance(vec3 P, vec3 N, vec3 V, vec3 albedo, float metallic, float roughness,
                       float ao)
{
    vec3 Lo = vec3(0.0);
    for (int i = 0; i < NUM_LIGHTS; ++i) {
        vec3 d = uLightPositions[i] - P;
        vec3 L = normalize(d);
        vec3 radiance = uLightColors[i] / dot(d, d);
        Lo += cookTorranceBRDF(N, V, L, albedo, metallic, roughness) * radiance *
              lambertCosine(N, L);
    }
    return Lo + 0.03 * albedo * ao;
}
)");
    Scene scene = loadScene(paths.scene(reflectance.desc->scene));
    StabilityResult r = stabilitySweep(renderer, reflectance, scene, {kit.path});
    EXPECT_GT(r.gpu.nonFinite(), 0) << describe(r.gpu);
    EXPECT_NE(r.firstProblem.find("scene lights at the extremes"), std::string::npos)
        << r.firstProblem;
    EXPECT_EQ(r.referenceNonFinite, 0);
}
