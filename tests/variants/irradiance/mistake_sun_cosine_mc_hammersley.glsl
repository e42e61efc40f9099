// mistake (for a sky with a sun): cosine-weighted Monte Carlo with 2048 Hammersley points, as the
// glTF Sample Viewer computes its Lambertian map: with pdf = cos / PI, E / PI is the plain mean of
// the radiance over the samples Right on skies without a sun; a sun of a fraction of a degree
// falls between its samples or nodes, so it is missed at most normals and over-counted at a few.
// expect: too coarse for a sun
vec3 irradianceAt(vec3 N)
{
    const uint n = 2048u;
    vec3 t = abs(N.z) < 0.999 ? normalize(cross(vec3(0.0, 0.0, 1.0), N)) : vec3(1.0, 0.0, 0.0);
    vec3 b = cross(N, t);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < n; ++i) {
        vec2 xi = hammersley(i, n);
        float phi = 2.0 * PI * xi.x;
        float cosTheta = sqrt(1.0 - xi.y);
        float sinTheta = sqrt(xi.y);
        vec3 L = t * (sinTheta * cos(phi)) + b * (sinTheta * sin(phi)) + N * cosTheta;
        sum += textureLod(uEnvironment, L, 0.0).rgb;
    }
    return sum / float(n);
}
