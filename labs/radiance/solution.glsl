// A point light sends its intensity equally in all directions; the same power spreads over
// a sphere whose area grows with the squared distance, so the radiance arriving at a point
// falls off as 1/d^2. Capped at d = 1 cm so a light sitting on the surface stays finite.
vec3 pointLightRadiance(vec3 lightColor, vec3 lightPos, vec3 worldPos)
{
    // BEGIN SOLUTION
    vec3 d = lightPos - worldPos;
    return lightColor / max(dot(d, d), 1e-4);
    // END SOLUTION
}
