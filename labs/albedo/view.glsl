// What this step shows: the base-colour texture decoded to linear albedo. The display encodes it
// back to sRGB for the screen, so a correct decode looks exactly like the texture itself; an
// undecoded texel (used as linear) comes out washed out and too bright.
vec3 view(Surface s)
{
    return srgbToLinear(s.albedoTexel);
}
