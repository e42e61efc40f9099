// expect: fits the Schlick factor (1 - cos)^4 where the reference has the Schlick factor (1 - cos)^5
// mistake: exponent typo, (1 - cos)^4 instead of ^5
vec3 fresnelSchlick(float cosTheta, vec3 F0)
{
    return F0 + (1.0 - F0) * pow(clamp(1.0 - cosTheta, 0.0, 1.0), 4.0);
}
