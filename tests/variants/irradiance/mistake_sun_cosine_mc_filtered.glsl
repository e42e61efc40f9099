// mistake (for a sky with a sun): cosine-weighted Monte Carlo with 2048 samples and filtered
// importance sampling (each sample reads the mip whose texel covers the solid angle 1 / (n pdf) it
// stands for), an own radical inverse by a loop and another tangent frame Right on skies without a
// sun; a sun of a fraction of a degree falls between its samples or nodes, so it is missed at most
// normals and over-counted at a few.
// expect: too coarse for a sun
float radicalInverseLoop(uint i)
{
    float result = 0.0, f = 0.5;
    for (uint k = i; k > 0u; k >>= 1u, f *= 0.5)
        if ((k & 1u) != 0u) result += f;
    return result;
}

vec3 irradianceAt(vec3 N)
{
    const uint n = 2048u;
    vec3 a = abs(N.x) < 0.6 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    vec3 t = normalize(a - N * dot(N, a));
    vec3 b = cross(t, N);
    float size = float(textureSize(uEnvironment, 0).x);
    float texel = 4.0 * PI / (6.0 * size * size);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < n; ++i) {
        float u = (float(i) + 0.5) / float(n), v = radicalInverseLoop(i);
        float phi = 2.0 * PI * v;
        float cosTheta = sqrt(1.0 - u);
        float sinTheta = sqrt(u);
        vec3 L = t * (sinTheta * cos(phi)) + b * (sinTheta * sin(phi)) + N * cosTheta;
        float pdf = max(cosTheta / PI, 1e-6);
        float lod = max(0.5 * log2(1.0 / (float(n) * pdf * texel)) + 1.0, 0.0);
        sum += textureLod(uEnvironment, L, lod).rgb;
    }
    return sum / float(n);
}
