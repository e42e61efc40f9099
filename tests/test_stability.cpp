// Every reference solution stays finite (and non-negative where the quantity is) on the
// extreme inputs, on the GPU and in the CPU reference.
#include <gtest/gtest.h>

#include "gl/context.h"
#include "stability.h"

using namespace pbrlab;

TEST(Stability, EveryReferenceIsFiniteOnTheExtremeSet) {
    auto context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR, paths.labs()};
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
