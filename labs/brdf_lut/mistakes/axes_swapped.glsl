// expect: the two inputs used the wrong way round
// mistake: the two inputs used the wrong way round (N.V taken as roughness and vice versa)
vec2 integrateBRDF(float NdotV, float roughness, uint sampleCount)
{
    float nv = clamp(roughness, 1e-4, 1.0);
    float r = NdotV;
    vec3 N = vec3(0.0, 0.0, 1.0);
    vec3 V = vec3(sqrt(1.0 - nv * nv), 0.0, nv);
    float k = r * r / 2.0;
    vec2 ab = vec2(0.0);
    for (uint i = 0u; i < sampleCount; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, sampleCount), N, r);
        vec3 L = reflect(-V, H);
        if (L.z > 0.0) {
            float VdotH = clamp(dot(V, H), 0.0, 1.0);
            float G = (nv / (nv * (1.0 - k) + k)) * (L.z / (L.z * (1.0 - k) + k));
            float gVis = G * VdotH / (max(H.z, 1e-4) * nv);
            float fc = pow(1.0 - VdotH, 5.0);
            ab += vec2(1.0 - fc, fc) * gVis;
        }
    }
    return ab / float(sampleCount);
}
