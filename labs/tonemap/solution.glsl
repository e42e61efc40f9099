// A display shows values in [0, 1] with a non-linear response; rendered radiance is linear
// and unbounded. Reinhard's operator x / (x + 1) compresses [0, inf) into [0, 1) while keeping
// dark values nearly linear, then gamma 1/2.2 encodes the result for the display.
vec3 displayEncode(vec3 hdr)
{
    // BEGIN SOLUTION
    vec3 h = max(hdr, vec3(0.0));
    vec3 c = h / (h + 1.0);
    return pow(c, vec3(1.0 / 2.2));
    // END SOLUTION
}
