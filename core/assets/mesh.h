// Triangle meshes on the CPU: what the G-buffer pass draws.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace pbrlab {

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;
    glm::vec4 tangent;  // xyz along +u, w = handedness (+1 or -1) of the bitangent
};

struct MeshData {
    std::vector<Vertex> vertices;
    std::vector<std::uint32_t> indices;  // triangles, counter-clockwise from outside
};

// Unit sphere centred at the origin; u runs around the equator (longitude), v from the north
// pole (v = 0) to the south pole (v = 1). Tangents follow +u, so handedness is +1.
MeshData makeUvSphere(int segments, int rings);

}  // namespace pbrlab
