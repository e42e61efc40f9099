// expect: no radical inverse
// mistake: y = i / n as well (no radical inverse): every point lies on the diagonal
vec2 hammersley(uint i, uint n)
{
    float x = float(i) / float(n);
    return vec2(x, x);
}
