// expect: the branches swapped
// mistake: boolean mix with the branches swapped (linear toe used above the knee)
vec3 srgbToLinear(vec3 c)
{
    vec3 low = c / 12.92;
    vec3 high = pow((c + 0.055) / 1.055, vec3(2.4));
    return mix(low, high, lessThanEqual(c, vec3(0.04045)));
}
