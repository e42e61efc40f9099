// What this step shows: N·L in grey on the sphere, white where it faces the light head-on,
// black on the side turned away (the terminator is where N·L reaches 0).
vec3 view(Surface s)
{
    return vec3(lambertCosine(s.normal, s.light));
}
