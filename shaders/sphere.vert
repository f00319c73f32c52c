#version 330 core
// Ray-cast sphere impostors. Each particle is drawn either as one point sprite (fast: one vertex
// per particle) or, when a sphere may cover more pixels than the largest point the driver
// draws, as an instanced four-vertex quad. Either way the primitive only has to cover the
// sphere's silhouette: the fragment shader casts the view ray through its pixel.

layout(location = 0) in vec4 a_sphere; // centre xyz [m], radius [m]
layout(location = 1) in vec4 a_color;  // sRGB, alpha unused

uniform mat4 u_view;
uniform mat4 u_proj;
uniform vec2 u_viewport; // [px]
uniform int u_ortho;
uniform int u_points;
uniform int u_clip_on;
uniform vec4 u_clip; // hidden where dot(u_clip.xyz, x) + u_clip.w > 0 (world space)

out vec3 v_center; // view space
out float v_radius;
flat out vec3 v_color;

/// A corner of the square that covers the silhouette, in the plane touching the sphere at its
/// point nearest the eye (so every hit point lies behind the primitive: depth only grows).
vec3 corner(vec3 c, float r, float d2, vec2 k)
{
    if (u_ortho != 0)
        return c + vec3(k * r, r);
    // The silhouette cone (half angle asin(r / |c|)) cut by that plane, at distance |c| - r from
    // the eye, is a circle of radius (|c| - r) r / sqrt(|c|^2 - r^2).
    float dc = sqrt(d2);
    vec3 w = -c / dc;
    vec3 u = normalize(cross(abs(w.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0), w));
    vec3 v = cross(w, u);
    float s = (dc - r) * r / sqrt(d2 - r * r);
    return c + r * w + s * (k.x * u + k.y * v);
}

void main()
{
    vec3 c = (u_view * vec4(a_sphere.xyz, 1.0)).xyz;
    float r = a_sphere.w;
    v_center = c;
    v_radius = r;
    v_color = a_color.rgb;
    float d2 = dot(c, c);
    bool hidden = u_clip_on != 0 && dot(u_clip.xyz, a_sphere.xyz) + u_clip.w > 0.0;
    if (hidden || (u_ortho == 0 && d2 <= r * r)) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside the clip volume: culled
        gl_PointSize = 1.0;
        return;
    }
    if (u_points == 0) {
        vec2 k = vec2((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0);
        gl_Position = u_proj * vec4(corner(c, r, d2, k), 1.0);
        return;
    }
    // Point sprite around the sphere's exact screen-space bounding box. In perspective, along
    // each screen axis a the tangent planes through the eye bound the projection at
    // P_aa (c_a z +- r sqrt(c_a^2 + z^2 - r^2)) / (z^2 - r^2) in normalised device coordinates,
    // z = -c.z the depth of the centre.
    vec2 scale = vec2(u_proj[0][0], u_proj[1][1]);
    vec2 mid, half_size;
    vec4 front;
    if (u_ortho != 0) {
        mid = (u_proj * vec4(c, 1.0)).xy;
        half_size = scale * r;
        front = u_proj * vec4(c + vec3(0.0, 0.0, r), 1.0);
    } else {
        float z = -c.z;
        float den = z * z - r * r;
        if (den <= 0.0) { // the sphere reaches the eye's plane: no finite box
            gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
            gl_PointSize = 1.0;
            return;
        }
        mid = scale * c.xy * z / den;
        half_size = scale * r * sqrt(c.xy * c.xy + den) / den;
        front = u_proj * vec4(c * (1.0 - r / sqrt(d2)), 1.0);
    }
    vec2 size = half_size * u_viewport; // full width and height in pixels
    gl_PointSize = max(size.x, size.y) + 1.0;
    gl_Position = vec4(mid, front.z / front.w, 1.0);
}
