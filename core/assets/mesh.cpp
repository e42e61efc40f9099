#include "assets/mesh.h"

#include <cmath>
#include <numbers>

namespace pbrlab {

MeshData makeUvSphere(int segments, int rings) {
    MeshData mesh;
    const double pi = std::numbers::pi;
    for (int r = 0; r <= rings; ++r) {
        double v = double(r) / rings, theta = v * pi;
        for (int s = 0; s <= segments; ++s) {
            double u = double(s) / segments, phi = u * 2.0 * pi;
            glm::dvec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                         -std::sin(theta) * std::sin(phi));
            // d(position)/du, which is well defined even at the poles (only its length
            // vanishes there), so the tangent frame never degenerates.
            glm::dvec3 t(-std::sin(phi), 0.0, -std::cos(phi));
            Vertex vert;
            vert.position = glm::vec3(n);
            vert.normal = glm::vec3(n);
            vert.uv = glm::vec2(float(u), float(v));  // glTF convention: v = 0 is the image top
            vert.tangent = glm::vec4(glm::vec3(t), 1.0f);
            mesh.vertices.push_back(vert);
        }
    }
    const int stride = segments + 1;
    for (int r = 0; r < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            std::uint32_t a = r * stride + s, b = a + stride;
            mesh.indices.insert(mesh.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
        }
    }
    return mesh;
}

}  // namespace pbrlab
