// correct: the fifth power as repeated products, clamp on the cosine
vec3 fresnelSchlick(float cosTheta, vec3 F0)
{
    float m = 1.0 - clamp(cosTheta, 0.0, 1.0);
    float m2 = m * m;
    float m5 = m2 * m2 * m;
    return F0 + (vec3(1.0) - F0) * m5;
}
