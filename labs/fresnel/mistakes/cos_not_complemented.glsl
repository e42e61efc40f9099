// expect: 1 - N.V in place of N.V
// mistake: cos^5 instead of (1 - cos)^5 (reflectance highest at normal incidence)
vec3 fresnelSchlick(float cosTheta, vec3 F0)
{
    return F0 + (1.0 - F0) * pow(clamp(cosTheta, 0.0, 1.0), 5.0);
}
