// expect: fits the reference without sin(theta)
// mistake: the solid angle's sin(theta) is missing (directions near N count as much as whole
// rings near the horizon)
vec3 irradianceAt(vec3 N)
{
    const int thetaSteps = 64;
    const int phiSteps = 256;
    float dTheta = 0.5 * PI / float(thetaSteps);
    float dPhi = 2.0 * PI / float(phiSteps);
    vec3 up = abs(N.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(0.0, 0.0, 1.0);
    vec3 right = normalize(cross(up, N));
    up = cross(N, right);
    float lod = max(log2(dTheta * float(textureSize(uEnvironment, 0).x)), 0.0);
    vec3 irradiance = vec3(0.0);
    for (int i = 0; i < thetaSteps; ++i) {
        float theta = (float(i) + 0.5) * dTheta;
        for (int j = 0; j < phiSteps; ++j) {
            float phi = (float(j) + 0.5) * dPhi;
            vec3 L = sin(theta) * cos(phi) * right + sin(theta) * sin(phi) * up + cos(theta) * N;
            irradiance += textureLod(uEnvironment, L, lod).rgb * cos(theta);
        }
    }
    return irradiance * dTheta * dPhi / PI;
}
