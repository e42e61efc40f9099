// expect: light from below the horizon counted
// |N.L| over the whole sphere: light from behind the surface counts too.
vec3 irradianceAt(vec3 N)
{
    const int thetaSteps = 48;
    const int phiSteps = 96;
    float dTheta = PI / float(thetaSteps);
    float dPhi = 2.0 * PI / float(phiSteps);
    vec3 up = abs(N.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(0.0, 0.0, 1.0);
    vec3 right = normalize(cross(up, N));
    up = cross(N, right);
    vec3 sum = vec3(0.0);
    for (int i = 0; i < thetaSteps; ++i) {
        float theta = (float(i) + 0.5) * dTheta;
        for (int j = 0; j < phiSteps; ++j) {
            float phi = (float(j) + 0.5) * dPhi;
            vec3 L = sin(theta) * cos(phi) * right + sin(theta) * sin(phi) * up + cos(theta) * N;
            sum += textureLod(uEnvironment, L, 2.0).rgb * abs(cos(theta)) * sin(theta);
        }
    }
    return sum * dTheta * dPhi / PI;
}
