// Precompute (step.json "precompute", kind square): the split-sum BRDF LUT with this step's
// integrateBRDF (Monte Carlo); texel centres map to x = N.V and y = roughness.
uniform vec2 uSize;
uniform uint uSampleCount;
layout(location = 0) out vec4 outColor;

void main()
{
    vec2 xy = gl_FragCoord.xy / uSize;
    outColor = vec4(integrateBRDF(xy.x, xy.y, uSampleCount), 0.0, 1.0);
}
