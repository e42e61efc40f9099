// mistake (for a sky with a sun): the classic hemisphere loop in spherical coordinates around N
// (64 x 256 midpoint grid, weight cos(theta) sin(theta)), reading a mip whose texels match the
// sample spacing Right on skies without a sun; a sun of a fraction of a degree falls between its
// samples or nodes, so it is missed at most normals and over-counted at a few.
// expect: too coarse for a sun
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
            vec3 tangentSample = vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
            vec3 L = tangentSample.x * right + tangentSample.y * up + tangentSample.z * N;
            irradiance += textureLod(uEnvironment, L, lod).rgb * cos(theta) * sin(theta);
        }
    }
    return irradiance * dTheta * dPhi / PI;
}
