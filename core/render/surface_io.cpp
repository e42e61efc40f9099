#include "render/surface_io.h"

#include "util/error.h"

namespace pbrlab {

std::vector<Image> packSurfaces(const std::vector<Surface>& surfaces, int width, int height) {
    std::vector<Image> images(kProbeTextures);
    for (auto& im : images) {
        im.width = width;
        im.height = height;
        im.channels = 4;
        im.pixels.assign(size_t(width) * height * 4, 0.0f);
    }
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const Surface& s = surfaces[size_t(y) * width + x];
            auto put = [&](int t, glm::dvec4 v) {
                for (int c = 0; c < 4; ++c) images[size_t(t)].at(x, y, c) = float(v[c]);
            };
            put(0, {s.position, s.covered ? 1 : 0});
            put(1, {s.normal, s.roughness});
            put(2, s.tangent);
            put(3, {s.uv, s.metallic, s.ao});
            // Emission rides in the alpha channels (the G-buffer's layout).
            put(4, {s.albedoTexel, s.emissive.r});
            put(5, {s.albedo, s.emissive.g});
            put(6, {s.normalTexel, s.emissive.b});
            put(7, {s.view, 0});
            put(8, {s.light, 0});
            put(9, {s.lightPosition, 0});
            put(10, {s.lightColor, 0});
            put(11, s.extra);
        }
    return images;
}

std::vector<Surface> unpackSurfaces(const std::vector<Image>& t, const glm::dvec3& cameraPosition,
                                    const ref::PointLight& firstLight) {
    if (t.size() != size_t(kGBufferTextures) && t.size() != size_t(kProbeTextures))
        throw Error("unpackSurfaces: expected 7 or 12 textures");
    const bool probe = t.size() == size_t(kProbeTextures);
    const int w = t[0].width, h = t[0].height;
    std::vector<Surface> out(size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            auto get = [&](int i) {
                const Image& im = t[size_t(i)];
                return glm::dvec4(im.at(x, y, 0), im.at(x, y, 1), im.at(x, y, 2), im.at(x, y, 3));
            };
            Surface& s = out[size_t(y) * w + x];
            glm::dvec4 t0 = get(0), t1 = get(1), t3 = get(3);
            s.covered = t0.w > 0.5;
            s.position = glm::dvec3(t0);
            s.normal = glm::dvec3(t1);
            s.roughness = t1.w;
            s.tangent = get(2);
            s.uv = glm::dvec2(t3);
            s.metallic = t3.z;
            s.ao = t3.w;
            const glm::dvec4 t4 = get(4), t5 = get(5), t6 = get(6);
            s.albedoTexel = glm::dvec3(t4);
            s.albedo = glm::dvec3(t5);
            s.normalTexel = glm::dvec3(t6);
            s.emissive = {t4.w, t5.w, t6.w};
            if (probe) {
                s.view = glm::dvec3(get(7));
                s.light = glm::dvec3(get(8));
                s.lightPosition = glm::dvec3(get(9));
                s.lightColor = glm::dvec3(get(10));
                s.extra = get(11);
            } else {
                s.view = ref::safeNormalize(cameraPosition - s.position, {0, 0, 1});
                s.lightPosition = firstLight.position;
                s.lightColor = firstLight.color;
                s.light = ref::safeNormalize(s.lightPosition - s.position, {0, 0, 0});
                s.extra = glm::dvec4(0);
            }
        }
    return out;
}

}  // namespace pbrlab
