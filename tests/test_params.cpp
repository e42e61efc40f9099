#include <gtest/gtest.h>

#include "pbrlab/params.h"
#include "util/error.h"

using namespace pbrlab;

namespace {
std::vector<ParamDecl> decls() {
    return {floatParam("roughness", 0.5, 0, 1, "GGX roughness"),
            floatParam("exposure", 1, 0.01, 100, "Exposure", true),
            intParam("samples", 64, 1, 4096, "Sample count"),
            boolParam("clamp", true, "Clamp"),
            colorParam("albedo", {1, 0, 0}, "Base colour"),
            enumParam("view", 0, {"value", "error"}, "What to show"),
            directionParam("light_dir", {0, 0, 2}, "Light direction")};
}
std::string errorOf(const std::string& assignment) {
    auto d = decls();
    ParamValues v(d);
    try {
        applyAssignment(d, v, assignment);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST(Params, DefaultsAndValidAssignments) {
    auto d = decls();
    ParamValues v(d);
    EXPECT_EQ(v.number("roughness"), 0.5);
    EXPECT_EQ(v.vector("light_dir"), glm::dvec3(0, 0, 1));  // default normalised
    applyAssignment(d, v, "roughness=0.25");
    applyAssignment(d, v, "samples=128");
    applyAssignment(d, v, "clamp=false");
    applyAssignment(d, v, "albedo=0.5,0.25,1");
    applyAssignment(d, v, "view=error");
    applyAssignment(d, v, "light_dir=0,3,4");
    EXPECT_EQ(v.number("roughness"), 0.25);
    EXPECT_EQ(v.number("samples"), 128);
    EXPECT_EQ(v.number("clamp"), 0);
    EXPECT_EQ(v.vector("albedo"), glm::dvec3(0.5, 0.25, 1));
    EXPECT_EQ(v.number("view"), 1);
    EXPECT_NEAR(v.vector("light_dir").y, 0.6, 1e-15);
}

TEST(Params, UnknownNameListsTheKnownOnes) {
    std::string m = errorOf("roughnes=0.3");
    EXPECT_NE(m.find("unknown parameter 'roughnes'"), std::string::npos) << m;
    EXPECT_NE(m.find("roughness: float in [0, 1]"), std::string::npos) << m;
    EXPECT_NE(m.find("view: one of value|error"), std::string::npos) << m;
}

TEST(Params, BadValuesSayWhatIsAllowed) {
    EXPECT_NE(errorOf("roughness=1.5").find("out of range; expected float in [0, 1]"),
              std::string::npos);
    EXPECT_NE(errorOf("roughness=abc").find("not a number"), std::string::npos);
    EXPECT_NE(errorOf("roughness=nan").find("not a number"), std::string::npos);
    EXPECT_NE(errorOf("samples=1.5").find("not an integer"), std::string::npos);
    EXPECT_NE(errorOf("clamp=maybe").find("not a boolean"), std::string::npos);
    EXPECT_NE(errorOf("albedo=1,2").find("three comma-separated"), std::string::npos);
    EXPECT_NE(errorOf("albedo=1,0,2").find("component out of range"), std::string::npos);
    EXPECT_NE(errorOf("view=other").find("unknown choice"), std::string::npos);
    EXPECT_NE(errorOf("light_dir=0,0,0").find("zero vector"), std::string::npos);
    EXPECT_NE(errorOf("roughness").find("expected name=value"), std::string::npos);
}
