// Specular image-based lighting by Monte Carlo, as in step `mc_specular`, with the half vectors
// drawn from the normals visible from V (step `vndf`). The density of L = reflect(-V, H) is
// then D_V(H) / (4 V.H) = G1(V) D(H) / (4 N.V), and the estimator f (N.L) / pdf loses D, the
// 4, N.L and N.V:
//     (1/n) sum  L_env(L) F(V.H) G(N.V, N.L) / G1(V)      over samples with N.L > 0.
// G is the lab's Smith-Schlick-GGX for image-based light (k = roughness^2 / 2), as in
// mc_specular; G1(V) is the visible normals' own, Smith's exact masking of GGX,
// G1(V) = 2 / (1 + sqrt(1 + alpha^2 tan^2(theta_V))).

// Schlick-GGX with k = alpha / 2, alpha floored (alpha^2 >= 1e-7) as the samplers floor it.
float pbrlab_vndfGeometrySchlickGGX(float NdotX, float roughness)
{
    float x = max(NdotX, 0.0);
    float k = max(roughness * roughness, 3.1622777e-4) * 0.5;
    return x / (x * (1.0 - k) + k);
}

vec3 specularIBLVisible(vec3 N, vec3 V, vec3 F0, float roughness, uint sampleCount)
{
    // BEGIN SOLUTION
    float NdotV = max(dot(N, V), 1e-4);
    float alpha = max(roughness * roughness, 3.1622777e-4);
    // tan^2 = (1 - cos^2) / cos^2, written so that it stays finite at N.V = 1e-4.
    float tan2 = max(1.0 - NdotV * NdotV, 0.0) / (NdotV * NdotV);
    float G1v = 2.0 / (1.0 + sqrt(1.0 + alpha * alpha * tan2));
    float Gv = pbrlab_vndfGeometrySchlickGGX(NdotV, roughness);
    uint n = max(sampleCount, 1u);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < n; ++i) {
        vec3 H = importanceSampleVNDF(hammersley(i, n), N, V, roughness);
        float VdotH = max(dot(V, H), 0.0);
        vec3 L = 2.0 * VdotH * H - V;
        float NdotL = dot(N, L);
        if (NdotL > 0.0) {
            float G = Gv * pbrlab_vndfGeometrySchlickGGX(NdotL, roughness);
            sum += textureLod(uEnvironment, L, 0.0).rgb * fresnelSchlick(VdotH, F0) * (G / G1v);
        }
    }
    return sum / float(n);
    // END SOLUTION
}
