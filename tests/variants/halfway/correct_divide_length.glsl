// correct: divides by the length itself, with its own guard for the degenerate case
vec3 halfwayVector(vec3 L, vec3 V)
{
    vec3 h = V + L;
    float len = length(h);
    return len > 1e-5 ? h / len : vec3(0.0);
}
