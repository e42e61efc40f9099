// mistake (for a sky with a sun): cosine-weighted Monte Carlo with 2048 Hammersley points under a
// Cranley-Patterson rotation (one random offset modulo 1 from SEED, the same at every N), filtered
// importance sampling (each sample reads the mip whose texel covers the solid angle 1 / (n pdf) it
// stands for) and a frame from the world's up axis. Right on skies without a sun; a sun of a
// fraction of a degree falls between its samples or nodes, so it is missed at most normals and
// over-counted at a few.
// expect: too coarse for a sun
const uint SEED = 0u;

uint rotationHash(uint x)
{
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

vec3 irradianceAt(vec3 N)
{
    const uint n = 2048u;
    vec3 up = abs(N.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 t = normalize(cross(up, N));
    vec3 b = cross(N, t);
    vec2 shift = vec2(float(rotationHash(2u * SEED + 1u) >> 8u),
                      float(rotationHash(2u * SEED + 2u) >> 8u)) / 16777216.0;
    float size = float(textureSize(uEnvironment, 0).x);
    float texel = 4.0 * PI / (6.0 * size * size);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < n; ++i) {
        vec2 xi = fract(vec2((float(i) + 0.5) / float(n),
                             float(bitfieldReverse(i)) * 2.3283064e-10) + shift);
        float cosTheta = sqrt(1.0 - xi.x);
        float sinTheta = sqrt(xi.x);
        float phi = 2.0 * PI * xi.y;
        vec3 L = t * (sinTheta * cos(phi)) + b * (sinTheta * sin(phi)) + N * cosTheta;
        float pdf = max(cosTheta / PI, 1e-6);
        float lod = max(0.5 * log2(1.0 / (float(n) * pdf * texel)) + 1.0, 0.0);
        sum += textureLod(uEnvironment, L, lod).rgb;
    }
    return sum / float(n);
}
