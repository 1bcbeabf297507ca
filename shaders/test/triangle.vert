#version 450
// Positions straight from a vertex buffer, already in clip space (z = 0, w = 1).
layout(location = 0) in vec2 position;
void main() { gl_Position = vec4(position, 0.0, 1.0); }
