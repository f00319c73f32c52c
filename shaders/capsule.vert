#version 330 core
// Ray-cast capsule impostors (rods: the points within r of the segment x +- a). Each particle is
// drawn as the front faces of a box that holds the capsule (14 vertices of a triangle strip
// round a cube, instanced; back faces culled), in perspective and orthographic views alike: the
// box's faces cover the capsule's whole projection, and lie in front of every point of it, so
// the fragment shader's depth only grows from the primitive's. The fragment shader casts the
// view ray through its pixel.

layout(location = 0) in vec4 a_sphere; // centre xyz [m], radius [m]
layout(location = 1) in vec3 a_axis;   // half the shaft, h u [m] (zero: a sphere)
layout(location = 2) in vec4 a_color;  // sRGB, alpha unused

uniform mat4 u_view;
uniform mat4 u_proj;
uniform vec2 u_viewport; // [px]
uniform int u_ortho;
uniform int u_clip_on;
uniform vec4 u_clip; // hidden where dot(u_clip.xyz, x) + u_clip.w > 0 (world space)

flat out vec3 v_center; // view space
flat out vec3 v_axis;   // view space
flat out float v_radius;
flat out vec3 v_color;

/// Corner k of the cube [-1, 1]^3 along a strip that covers its six faces, each triangle
/// counter-clockwise seen from outside (the bit masks pick x, y and z of the corners).
vec3 strip_corner(int k)
{
    int b = 1 << k;
    return vec3((0x287A & b) != 0 ? 1.0 : -1.0, (0x02AF & b) != 0 ? 1.0 : -1.0,
                (0x31E3 & b) != 0 ? 1.0 : -1.0);
}

void main()
{
    vec3 c = (u_view * vec4(a_sphere.xyz, 1.0)).xyz;
    vec3 a = mat3(u_view) * a_axis;
    float r = a_sphere.w;
    v_center = c;
    v_axis = a;
    v_radius = r;
    v_color = a_color.rgb;
    if (u_clip_on != 0 && dot(u_clip.xyz, a_sphere.xyz) + u_clip.w > 0.0) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside the clip volume: culled
        return;
    }
    // The box's frame: u along the shaft; e turned about it to lie across the line of sight, so
    // that the box shows the eye a face of width 2r rather than a diagonal.
    float h = length(a);
    vec3 u = h > 0.0 ? a / h : vec3(1.0, 0.0, 0.0);
    vec3 sight = u_ortho != 0 ? vec3(0.0, 0.0, 1.0) : c;
    vec3 e = cross(u, sight);
    if (dot(e, e) <= 1e-12 * dot(sight, sight))
        e = cross(u, abs(u.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0));
    e = normalize(e);
    vec3 f = cross(u, e); // (u, e, f) right-handed: the strip's winding is kept
    // Grown by a pixel at the box's far end (so by more everywhere nearer), so that every pixel
    // whose centre sees the capsule is wholly covered, as a sphere's point sprite covers it: with
    // multisampling, the edge pixels are then the shader's alone.
    float pixel = 2.0 / (u_proj[1][1] * u_viewport.y); // at unit depth, or anywhere when parallel
    float grow = u_ortho != 0 ? pixel : pixel * max(h + r - c.z, 0.0);
    vec3 k = strip_corner(gl_VertexID);
    vec3 corner = c + k.x * (h + r + grow) * u + (r + grow) * (k.y * e + k.z * f);
    gl_Position = u_proj * vec4(corner, 1.0);
}
