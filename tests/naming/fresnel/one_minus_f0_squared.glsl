// expect: (1 - F0) in front of the Schlick factor applied twice
// (1 - F0) used twice: once in a helper variable, once again in the sum.
vec3 fresnelSchlick(float cosTheta, vec3 F0)
{
    vec3 weight = 1.0 - F0;
    vec3 rim = weight * pow(clamp(1.0 - cosTheta, 0.0, 1.0), 5.0);
    return F0 + weight * rim;
}
