// Turns the number of occupied blocks into a dispatch command: work groups in rows of
// kRow (the x dimension has a limit), the last row partly idle.
layout(local_size_x = 1) in;

layout(std430, binding = 3) buffer BlockList { uint count; uint dispatch[3]; uint block[]; };

const uint kRow = 32768u;

void main() {
  dispatch[0] = min(count, kRow);
  dispatch[1] = (count + kRow - 1u) / kRow;
  dispatch[2] = 1u;
}
