#version 330 core
// u_mode 0: flat colour; 1: text (glyph coverage in the red channel); 2: colour map lookup.
in vec2 v_uv;
in vec4 v_color;
uniform int u_mode;
uniform sampler2D u_texture;
out vec4 o_color;
void main()
{
    if (u_mode == 1)
        o_color = vec4(v_color.rgb, v_color.a * texture(u_texture, v_uv).r);
    else if (u_mode == 2)
        o_color = vec4(texture(u_texture, v_uv).rgb, 1.0);
    else
        o_color = v_color;
}
