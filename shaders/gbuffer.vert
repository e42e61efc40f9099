// G-buffer pass: world-space position, normal, tangent and uv of each visible surface point.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;
layout(location = 3) in vec4 aTangent;

uniform mat4 uModel;
uniform mat3 uNormalMatrix;
uniform mat4 uViewProjection;

out vec3 vPosition;
out vec3 vNormal;
out vec2 vUv;
out vec4 vTangent;

void main()
{
    vec4 world = uModel * vec4(aPosition, 1.0);
    vPosition = world.xyz;
    vNormal = uNormalMatrix * aNormal;
    vTangent = vec4(mat3(uModel) * aTangent.xyz, aTangent.w);
    vUv = aUv;
    gl_Position = uViewProjection * world;
}
