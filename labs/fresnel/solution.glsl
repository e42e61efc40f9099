// Fresnel effect (Schlick's approximation): every surface becomes a mirror at grazing angles.
// Reflectance rises from F0 at normal incidence (cosTheta = 1) to 1 at grazing incidence
// (cosTheta = 0) following (1 - cosTheta)^5.
vec3 fresnelSchlick(float cosTheta, vec3 F0)
{
    // BEGIN SOLUTION
    return F0 + (1.0 - F0) * pow(clamp(1.0 - cosTheta, 0.0, 1.0), 5.0);
    // END SOLUTION
}
