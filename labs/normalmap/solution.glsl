// A normal map stores the shading normal in tangent space (x along the tangent, y along the
// bitangent, z along the surface normal), each component remapped to [0, 1]. Decoding it
// needs an orthonormal frame at the point: T made perpendicular to N, B = N x T flipped by
// the handedness in tangent.w (mirrored UVs).

// A unit vector perpendicular to N, for a missing tangent or one parallel to N: the x axis
// (the y axis when N is close to x) projected onto the plane of N.
vec3 pbrlab_perpendicular(vec3 N)
{
    vec3 axis = abs(N.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    return pbrlab_safeNormalize(axis - N * dot(N, axis), axis);
}

vec3 normalFromMap(vec3 N, vec4 tangent, vec3 mapTexel)
{
    // BEGIN SOLUTION
    vec3 n = mapTexel * 2.0 - 1.0;
    vec3 T = pbrlab_safeNormalize(tangent.xyz - N * dot(N, tangent.xyz), pbrlab_perpendicular(N));
    vec3 B = cross(N, T) * (tangent.w < 0.0 ? -1.0 : 1.0);
    return pbrlab_safeNormalize(T * n.x + B * n.y + N * n.z, N);
    // END SOLUTION
}
