// A correct variant written as Filament's shading code is (its own words here): the lobe
// computed by hand with the lesson's + 0.001 denominator, the compensation
// energyCompensation = 1 + f0 (1 / dfg - 1) applied to it.
vec3 cookTorranceBRDFMultiscatter(vec3 N, vec3 V, vec3 L, vec3 albedo, float metallic, float roughness)
{
    vec3 f0 = mix(vec3(0.04), albedo, metallic);
    vec3 h = normalize(L + V);
    float NoV = max(dot(N, V), 0.0), NoL = max(dot(N, L), 0.0), NoH = max(dot(N, h), 0.0);
    float a = max(roughness * roughness, 1e-3), a2 = a * a;  // no 0 / 0 at roughness 0
    float d = NoH * NoH * (a2 - 1.0) + 1.0;
    float D = a2 / (PI * d * d);
    float k = (roughness + 1.0) * (roughness + 1.0) / 8.0;
    float G = NoV / (NoV * (1.0 - k) + k) * (NoL / (NoL * (1.0 - k) + k));
    vec3 F = f0 + (1.0 - f0) * pow(clamp(1.0 - dot(h, V), 0.0, 1.0), 5.0);
    vec3 Fr = D * G * F / (4.0 * NoV * NoL + 0.001);
    float dfg = dot(texture(uBrdfLut, vec2(NoV, roughness)).rg, vec2(1.0));
    vec3 energyCompensation = 1.0 + f0 * (1.0 / dfg - 1.0);
    vec3 Fd = (1.0 - F) * (1.0 - metallic) * albedo / PI;
    return Fd + Fr * energyCompensation;
}
