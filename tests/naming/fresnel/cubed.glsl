// expect: (1 - cos)^3 where
// The Schlick factor written out by hand, one factor short of two.
vec3 fresnelSchlick(float cosTheta, vec3 F0)
{
    float m = clamp(1.0 - cosTheta, 0.0, 1.0);
    float s = m * m * m;
    return F0 + (vec3(1.0) - F0) * s;
}
