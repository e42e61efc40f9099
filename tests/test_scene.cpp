#include <gtest/gtest.h>

#include "pbrlab/error.h"
#include "pbrlab/scene.h"
#include "test_support.h"

using namespace pbrlab;

namespace {
std::string loadError(const std::string& json) {
    test::TempDir dir;
    auto file = dir.write("scene.json", json);
    try {
        loadScene(file);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}
const char* kLight = R"("lights": [{"position": [0, 0, 5], "color": [1, 1, 1]}])";
}  // namespace

TEST(Scene, LoadsTheProjectScenes) {
    for (const char* name : {"sphere"}) {
        Scene s = loadScene(std::string(PBRLAB_SOURCE_DIR) + "/assets/scenes/" + name + ".json");
        EXPECT_FALSE(s.objects.empty()) << name;
        EXPECT_FALSE(s.lights.empty()) << name;
    }
}

TEST(Scene, ErrorsNameTheFileAndTheField) {
    std::string m =
        loadError(std::string("{") + kLight + R"(, "objects": [{"material": {"roughness": 2}}]})");
    EXPECT_NE(m.find("scene.json: field 'objects[0].material.roughness'"), std::string::npos) << m;
    m = loadError(std::string("{") + kLight + R"(, "objects": [{"material": "steel"}]})");
    EXPECT_NE(m.find("'objects[0].material': no material named \"steel\""), std::string::npos) << m;
    m = loadError(R"({"lights": [], "objects": []})");
    EXPECT_NE(m.find("'lights'"), std::string::npos) << m;
    m = loadError(std::string("{") + kLight + R"(, "objects": [{"material": {}, "colour": 1}]})");
    EXPECT_NE(m.find("'objects[0].colour': unknown field"), std::string::npos) << m;
    m = loadError(std::string("{") + kLight +
                  R"(, "objects": [{"material": {"albedoMap": "missing.png"}}]})");
    EXPECT_NE(m.find("missing.png does not exist"), std::string::npos) << m;
    m = loadError("{ not json");
    EXPECT_NE(m.find("scene.json: not valid JSON"), std::string::npos) << m;
    EXPECT_NE(loadError("").find("not valid JSON"), std::string::npos);
}
