// Lambert's cosine law: a beam hitting the surface at an angle spreads over a larger area,
// so the irradiance it delivers scales with cos(theta) = N.L. Light from below the surface
// delivers nothing, hence the clamp at zero.
float lambertCosine(vec3 N, vec3 L)
{
    // BEGIN SOLUTION
    return max(dot(N, L), 0.0);
    // END SOLUTION
}
