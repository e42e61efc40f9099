// Entry point of every module view: evaluates the module's view(Surface) per pixel into a
// float target (alpha = 1 where a surface was evaluated).
layout(location = 0) out vec4 outValue;

void main()
{
    Surface s = loadSurface();
    outValue = s.covered ? vec4(view(s), 1.0) : vec4(0.0);
}
