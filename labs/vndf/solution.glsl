// Sampling the GGX normals visible from V (Heitz 2018, "Sampling the GGX Distribution of
// Visible Normals", JCGT 7(4)). Step `importance` drew H with density D(H) (N.H): every
// microfacet, also those facing away from V, which reflect nothing towards it, and those hidden
// behind others. The visible normals have density
//     D_V(H) = G1(V) max(V.H, 0) D(H) / (N.V)
// per steradian: each microfacet weighted by its projected area seen from V. Heitz samples it
// exactly: stretch the view into the configuration where the GGX lobe is a hemisphere, pick a
// point of the disk that hemisphere shows to the view, and unstretch. The sample is built in a
// tangent frame (T, B, N) and returned in world space.
vec3 importanceSampleVNDF(vec2 Xi, vec3 N, vec3 V, float roughness)
{
    // BEGIN SOLUTION
    // alpha floored like importanceSampleGGX's (alpha^2 >= 1e-7).
    float a = max(roughness * roughness, 3.1622777e-4);
    vec2 u = clamp(Xi, 0.0, 1.0);
    vec3 up = abs(N.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 T = normalize(cross(up, N));
    vec3 B = cross(N, T);
    // V in the frame, kept above the horizon (V below it is seen at grazing incidence).
    vec3 Ve = vec3(dot(V, T), dot(V, B), max(dot(V, N), 1e-4));
    // 1. The view in the stretched configuration, where the lobe is a hemisphere.
    vec3 Vh = normalize(vec3(a * Ve.x, a * Ve.y, Ve.z));
    // 2. A frame around it (any T1 perpendicular to Vh when Vh = +z).
    float lensq = Vh.x * Vh.x + Vh.y * Vh.y;
    vec3 T1 = lensq > 0.0 ? vec3(-Vh.y, Vh.x, 0.0) * inversesqrt(lensq) : vec3(1.0, 0.0, 0.0);
    vec3 T2 = cross(Vh, T1);
    // 3. A uniform point of the unit disk, squeezed onto the part of it the hemisphere shows
    //    to Vh (the half disk behind the horizon shrinks by s).
    float r = sqrt(u.x);
    float phi = 2.0 * PI * u.y;
    float t1 = r * cos(phi);
    float t2 = r * sin(phi);
    float s = 0.5 * (1.0 + Vh.z);
    t2 = (1.0 - s) * sqrt(max(1.0 - t1 * t1, 0.0)) + s * t2;
    // 4. Onto the hemisphere, then 5. unstretched back to the lobe.
    vec3 Nh = t1 * T1 + t2 * T2 + sqrt(max(0.0, 1.0 - t1 * t1 - t2 * t2)) * Vh;
    vec3 He = normalize(vec3(a * Nh.x, a * Nh.y, max(0.0, Nh.z)));
    return normalize(T * He.x + B * He.y + N * He.z);
    // END SOLUTION
}
