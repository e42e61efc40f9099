// What this step shows: the perturbed world-space normal as a colour (0.5 + 0.5 n): the
// sphere's smooth normal gradient (red to the right, green up, blue towards the camera) with
// the plates' seams, rivets and dents from the normal map standing out in relief.
vec3 view(Surface s)
{
    return normalFromMap(s.normal, s.tangent, s.normalTexel);
}
