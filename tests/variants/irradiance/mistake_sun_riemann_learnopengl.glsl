// mistake (for a sky with a sun): LearnOpenGL's Riemann sum over theta and phi at half its
// resolution (step 0.05 rad instead of 0.025), left end points, normalised by the sample count; a
// frame that stays defined when N is straight up or down Right on skies without a sun; a sun of a
// fraction of a degree falls between its samples or nodes, so it is missed at most normals and
// over-counted at a few.
// expect: too coarse for a sun
vec3 irradianceAt(vec3 N)
{
    vec3 up = abs(N.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 right = normalize(cross(up, N));
    up = normalize(cross(N, right));
    float sampleDelta = 0.05;
    float nrSamples = 0.0;
    vec3 irradiance = vec3(0.0);
    for (float phi = 0.0; phi < 2.0 * PI; phi += sampleDelta) {
        for (float theta = 0.0; theta < 0.5 * PI; theta += sampleDelta) {
            vec3 tangentSample = vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
            vec3 sampleVec = tangentSample.x * right + tangentSample.y * up + tangentSample.z * N;
            irradiance += texture(uEnvironment, sampleVec).rgb * cos(theta) * sin(theta);
            nrSamples++;
        }
    }
    // PI * sum / count is E / PI for LearnOpenGL's map too (its diffuse is irradiance * albedo).
    return PI * irradiance * (1.0 / nrSamples);
}
