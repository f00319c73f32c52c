#version 330 core
#extension GL_ARB_conservative_depth : enable
// The view ray through this pixel against the sphere: discard on a miss, else the depth of the
// hit point (so intersecting spheres cut each other correctly) and a headlight-style shade.

in vec3 v_center;
in float v_radius;
flat in vec3 v_color;

uniform mat4 u_proj;
uniform vec2 u_viewport; // [px]
uniform int u_ortho;
uniform int u_lighting;
uniform vec3 u_light; // unit, view space, towards the light

out vec4 o_color;
#ifdef GL_ARB_conservative_depth
layout(depth_greater) out float gl_FragDepth;
#endif

void main()
{
    // The pixel centre in normalised device coordinates, back to view space (the projections
    // are glm's symmetric perspective and orthographic ones).
    vec2 ndc = 2.0 * gl_FragCoord.xy / u_viewport - 1.0;
    float r2 = v_radius * v_radius;
    vec3 hit;
    if (u_ortho != 0) {
        // Rays along -z: the offset from the centre in the view plane, without cancellation.
        vec2 p = (ndc - u_proj[3].xy) / vec2(u_proj[0][0], u_proj[1][1]);
        vec2 q = p - v_center.xy;
        float h = r2 - dot(q, q);
        if (h < 0.0)
            discard;
        hit = vec3(p, v_center.z + sqrt(h));
    } else {
        // Ray t d from the eye: closest approach to the centre, then back along the ray.
        vec3 d = normalize(vec3(ndc.x / u_proj[0][0], ndc.y / u_proj[1][1], -1.0));
        float tc = dot(v_center, d);
        vec3 q = v_center - tc * d;
        float h = r2 - dot(q, q);
        if (h < 0.0)
            discard;
        hit = (tc - sqrt(h)) * d;
    }
    vec4 clip = u_proj * vec4(hit, 1.0);
    gl_FragDepth = 0.5 * clip.z / clip.w + 0.5;
    vec3 color = v_color;
    if (u_lighting != 0) {
        vec3 n = (hit - v_center) / v_radius;
        vec3 view = u_ortho != 0 ? vec3(0.0, 0.0, 1.0) : normalize(-hit);
        float diffuse = max(dot(n, u_light), 0.0);
        float specular = pow(max(dot(n, normalize(u_light + view)), 0.0), 48.0);
        color = color * (0.35 + 0.65 * diffuse) + vec3(0.22 * specular);
    }
    o_color = vec4(color, 1.0);
}
