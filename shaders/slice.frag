#version 330 core
in vec2 v_uv;
uniform sampler2D u_cells; // sRGB colour per cell
uniform float u_alpha;
out vec4 o_color;
void main()
{
    o_color = vec4(texture(u_cells, v_uv).rgb, u_alpha);
}
