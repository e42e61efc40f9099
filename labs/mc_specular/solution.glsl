// Specular image-based lighting by brute force: the reflectance integral of the Cook-Torrance
// lobe over the environment, estimated with n GGX-distributed half vectors (Hammersley points)
// and the reflected light directions L = reflect(-V, H). With pdf(L) = D (N.H) / (4 V.H) the
// estimator f (N.L) / pdf loses D and the 4 N.L:
//     (1/n) sum  L_env(L) F(V.H) G(N.V, N.L) (V.H) / ((N.H) (N.V))      over samples with N.L > 0.
// G is Smith-Schlick-GGX with the IBL remapping k = roughness^2 / 2.

// Schlick-GGX with k = alpha / 2; alpha floored like D (1e-7 on alpha^2), which keeps k > 0
// (no 0/0 at N.X = 0) and the masking consistent with the lobe that is sampled.
float pbrlab_mcGeometrySchlickGGX(float NdotX, float roughness)
{
    float x = max(NdotX, 0.0);
    float k = max(roughness * roughness, 3.1622777e-4) * 0.5;
    return x / (x * (1.0 - k) + k);
}

vec3 specularIBLReference(vec3 N, vec3 V, vec3 F0, float roughness, uint sampleCount)
{
    // BEGIN SOLUTION
    // N.V floored: it divides the weight (1e-4 as in the LUT).
    float NdotV = max(dot(N, V), 1e-4);
    uint n = max(sampleCount, 1u);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < n; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, n), N, roughness);
        float VdotH = dot(V, H);
        vec3 L = 2.0 * VdotH * H - V;
        float NdotL = dot(N, L);
        if (NdotL > 0.0) {
            // N.H floored (it divides); V.H clamped (V below the horizon can make it < 0).
            float NdotH = max(dot(N, H), 1e-4);
            VdotH = max(VdotH, 0.0);
            float G = pbrlab_mcGeometrySchlickGGX(NdotV, roughness) *
                      pbrlab_mcGeometrySchlickGGX(NdotL, roughness);
            vec3 F = fresnelSchlick(VdotH, F0);
            sum += textureLod(uEnvironment, L, 0.0).rgb * F * (G * VdotH / (NdotH * NdotV));
        }
    }
    return sum / float(n);
    // END SOLUTION
}
