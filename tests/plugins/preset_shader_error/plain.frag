// The default pass: a copy of the input.
void main() {
    out_color = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
}
