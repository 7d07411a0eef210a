// One photon: added into the caustics map (additive blending).
out vec4 photons;
void main() { photons = vec4(1.0, 0.0, 0.0, 0.0); }
