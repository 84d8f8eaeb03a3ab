// The per-object table of the `fast` method on the GPU (README "Fast method"): per id present,
// its pixel count, depth sum over positive finite depths and albedo sum (clamped to [0, 1]),
// in an open-addressing hash table keyed by the id's bits. One invocation walks a run of 64
// pixels of a row and adds to the table once per run of equal ids, so the atomics follow the
// object boundaries, not the pixels. Sums are 64-bit fixed point (32 fraction bits) in two
// words: exact whatever the order the invocations add in.
layout(local_size_x = 64) in;

layout(std430, binding = 0) buffer Table { uint entries[]; };  // kTableWords per slot

uniform sampler2D u_id;
uniform sampler2D u_depth;
uniform sampler2D u_albedo;
uniform int u_slots;  // a power of two

const int kRun = 64;
const int kWords = 12;  // key, count, depth count, depth lo/hi, albedo r, g, b lo/hi, unused

bool is_object_id(float v) {
  return v >= 1.0 && v < 16777216.0 && floor(v) == v;
}

int find_or_insert(uint key) {
  uint mask = uint(u_slots - 1);
  uint h = (key * 2654435761u) & mask;
  for (int probe = 0; probe < u_slots; ++probe) {
    uint slot = (h + uint(probe)) & mask;
    uint previous = atomicCompSwap(entries[slot * kWords], 0u, key);
    if (previous == 0u || previous == key) return int(slot);
  }
  return -1;  // full: the id is left out
}

void add64(uint index, float value) {
  float v = max(value, 0.0);
  uint hi = uint(floor(v));
  uint lo = uint(fract(v) * 4294967296.0);
  uint before = atomicAdd(entries[index], lo);
  if (before + lo < before) hi += 1u;  // carry
  if (hi != 0u) atomicAdd(entries[index + 1u], hi);
}

void flush(float id, uint count, uint depth_count, float depth, vec3 albedo) {
  if (count == 0u) return;
  int slot = find_or_insert(floatBitsToUint(id));
  if (slot < 0) return;
  uint base = uint(slot) * uint(kWords);
  atomicAdd(entries[base + 1u], count);
  atomicAdd(entries[base + 2u], depth_count);
  add64(base + 3u, depth);
  add64(base + 5u, albedo.r);
  add64(base + 7u, albedo.g);
  add64(base + 9u, albedo.b);
}

void main() {
  ivec2 size = textureSize(u_id, 0);
  int runs_per_row = (size.x + kRun - 1) / kRun;
  int run = int(gl_GlobalInvocationID.x);
  int y = run / runs_per_row;
  if (y >= size.y) return;
  int x0 = (run % runs_per_row) * kRun;
  int x1 = min(x0 + kRun, size.x);
  // A run of equal ids is summed in the inner loop and flushed after it: llvmpipe executes an
  // `if` for every lane whether or not one takes it, so a flush inside the per-pixel loop ran
  // its atomics' lane loops at every pixel (about 1 ms of the pass's 10 at 720p; the same sums).
  int x = x0;
  while (x < x1) {
    float current = texelFetch(u_id, ivec2(x, y), 0).r;
    if (!is_object_id(current)) current = -1.0;
    uint count = 0u, depth_count = 0u;
    float depth = 0.0;
    vec3 albedo = vec3(0.0);
    for (; x < x1; ++x) {
      ivec2 p = ivec2(x, y);
      float id = texelFetch(u_id, p, 0).r;
      if (!is_object_id(id)) id = -1.0;
      if (id != current) break;
      if (id < 0.0) continue;
      ++count;
      float z = texelFetch(u_depth, p, 0).r;
      if (z > 0.0 && z < 3.0e38) {
        depth += z;
        ++depth_count;
      }
      vec3 a = texelFetch(u_albedo, p, 0).rgb;
      albedo += vec3(a.r >= 0.0 ? min(a.r, 1.0) : 0.0, a.g >= 0.0 ? min(a.g, 1.0) : 0.0,
                     a.b >= 0.0 ? min(a.b, 1.0) : 0.0);
    }
    if (current > 0.0) flush(current, count, depth_count, depth, albedo);
  }
}
