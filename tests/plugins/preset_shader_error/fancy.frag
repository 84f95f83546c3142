// The ultra preset's pass: line 4 names a variable that does not exist.
void main() {
    vec4 colour = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    out_color = colour * undeclared_gain;
}
