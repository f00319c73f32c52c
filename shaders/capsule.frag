#version 330 core
#extension GL_ARB_conservative_depth : enable
// The view ray through this pixel against the capsule: the side of the shaft's cylinder where
// the ray enters it between the shaft's ends, else the ball of the end it enters beyond. Discard
// on a miss; else the depth of the hit point (so capsules and spheres cut each other correctly)
// and the sphere shader's shading with the capsule's normal.

flat in vec3 v_center; // view space
flat in vec3 v_axis;   // view space
flat in float v_radius;
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

/// The sphere shader's ray cast, against the ball of radius v_radius about e: the same
/// expressions, so that a rod of zero length draws the pixels of a sphere. p is the pixel in the
/// view plane (parallel rays), d the unit ray from the eye (perspective).
bool ball(vec3 e, vec2 p, vec3 d, out vec3 hit, out vec3 n)
{
    float r2 = v_radius * v_radius;
    if (u_ortho != 0) {
        vec2 q = p - e.xy;
        float h = r2 - dot(q, q);
        if (h < 0.0)
            return false;
        hit = vec3(p, e.z + sqrt(h));
    } else {
        float tc = dot(e, d);
        vec3 q = e - tc * d;
        float h = r2 - dot(q, q);
        if (h < 0.0)
            return false;
        hit = (tc - sqrt(h)) * d;
    }
    n = (hit - e) / v_radius;
    return true;
}

/// The ray o + t d, o its point nearest the centre c, against the infinite cylinder of radius r
/// about the shaft's line c + s a: with m = o - c (so m.d = 0), |m + t d - s(t) a| = r is
/// A t^2 + 2 B t + C = 0 with A = |a x d|^2 (written so, not as a.a - (a.d)^2, to keep it exact
/// for rays near the axis), B = -(a.m)(a.d), C = a.a (m.m - r^2) - (a.m)^2. Returns SIDE for a
/// hit on the side within the shaft (hit and normal set), MISS when the ray passes the cylinder,
/// else the end (-1 or +1) whose ball the ray meets first if it meets the capsule at all.
const int MISS = 0, SIDE = 2;
int side(vec3 o, vec3 d, out vec3 hit, out vec3 n)
{
    vec3 a = v_axis, m = o - v_center, ad_cross = cross(a, d);
    float aa = dot(a, a), ad = dot(a, d), am = dot(a, m);
    float A = dot(ad_cross, ad_cross);
    if (A <= 1e-12 * aa) // along the axis: the end the ray reaches first
        return ad > 0.0 ? -1 : 1;
    float B = -am * ad, C = aa * (dot(m, m) - v_radius * v_radius) - am * am;
    float disc = B * B - A * C;
    if (disc < 0.0)
        return MISS;
    // The nearer root, in the form without cancellation.
    float root = sqrt(disc), q = root - B;
    float t = B > 0.0 ? -(B + root) / A : (q > 0.0 ? C / q : 0.0);
    float s = (am + t * ad) / aa;
    if (abs(s) > 1.0)
        return s > 0.0 ? 1 : -1;
    hit = o + t * d;
    n = (m + t * d - s * a) / v_radius;
    return SIDE;
}

void main()
{
    // The pixel centre in normalised device coordinates, back to view space (the projections
    // are glm's symmetric perspective and orthographic ones).
    vec2 ndc = 2.0 * gl_FragCoord.xy / u_viewport - 1.0;
    vec2 p = vec2(0.0);
    vec3 d, o;
    if (u_ortho != 0) {
        p = (ndc - u_proj[3].xy) / vec2(u_proj[0][0], u_proj[1][1]);
        d = vec3(0.0, 0.0, -1.0);
        o = vec3(p, v_center.z);
    } else {
        d = normalize(vec3(ndc.x / u_proj[0][0], ndc.y / u_proj[1][1], -1.0));
        o = dot(v_center, d) * d;
    }
    vec3 hit, n;
    int end = dot(v_axis, v_axis) > 0.0 ? side(o, d, hit, n) : 1;
    if (end == MISS || (end != SIDE && !ball(v_center + float(end) * v_axis, p, d, hit, n)))
        discard;
    vec4 clip = u_proj * vec4(hit, 1.0);
    gl_FragDepth = 0.5 * clip.z / clip.w + 0.5;
    vec3 color = v_color;
    if (u_lighting != 0) {
        vec3 view = u_ortho != 0 ? vec3(0.0, 0.0, 1.0) : normalize(-hit);
        float diffuse = max(dot(n, u_light), 0.0);
        float specular = pow(max(dot(n, normalize(u_light + view)), 0.0), 48.0);
        color = color * (0.35 + 0.65 * diffuse) + vec3(0.22 * specular);
    }
    o_color = vec4(color, 1.0);
}
