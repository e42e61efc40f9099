// correct: both Schlick-GGX terms written inline, clamp instead of max
float schlick(float x, float k)
{
    return x / (x * (1.0 - k) + k);
}

float geometrySmith(vec3 N, vec3 V, vec3 L, float roughness)
{
    float k = (roughness + 1.0) * (roughness + 1.0) / 8.0;
    return schlick(clamp(dot(N, L), 0.0, 1.0), k) * schlick(clamp(dot(N, V), 0.0, 1.0), k);
}
