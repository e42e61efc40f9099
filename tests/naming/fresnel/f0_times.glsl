// expect: F0 multiplying the Schlick factor
// F0 where (1 - F0) belongs.
vec3 fresnelSchlick(float cosTheta, vec3 F0)
{
    float factor = pow(clamp(1.0 - cosTheta, 0.0, 1.0), 5.0);
    return F0 + F0 * factor;
}
