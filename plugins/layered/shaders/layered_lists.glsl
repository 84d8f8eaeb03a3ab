// Short per-texel lists of the `fast` method (README "Fast method"): up to four layers per
// texel, keyed by 1 + the layer's slot in the GPU table (0: empty), with values per key in
// vec4s whose components follow the keys. A pass that gathers neighbours adds each
// neighbour's keys to its own list (the nearest taps first, so a texel within reach of more
// than four layers keeps the four nearest) and moves their values with the matrix
// `list_merge` returns: (m * values)[i] is the neighbour's value for this texel's key i.

// One-hot of the first free slot of `keys` (zero when none is free).
vec4 list_first_free(vec4 keys) {
  vec4 free = vec4(lessThan(keys, vec4(0.5)));
  return free * vec4(1.0, 1.0 - free.x, (1.0 - free.x) * (1.0 - free.y),
                     (1.0 - free.x) * (1.0 - free.y) * (1.0 - free.z));
}

// The slot of `key` in `keys` as a one-hot, taking the first free slot when it is not there
// (written with vector operations only: indexing by a computed slot is slow on llvmpipe).
vec4 list_slot(inout vec4 keys, float key) {
  if (!(key > 0.5)) return vec4(0.0);
  vec4 same = vec4(equal(keys, vec4(key)));
  vec4 slot = any(greaterThan(same, vec4(0.0))) ? same : list_first_free(keys);
  keys += slot * (key - keys);
  return slot;
}

// Adds the keys `tap` to the list `keys` where there is room; the matrix moving the tap's
// values to the list's slots (a key dropped for lack of room moves nowhere).
mat4 list_merge(inout vec4 keys, vec4 tap) {
  mat4 m;
  m[0] = list_slot(keys, tap.x);
  m[1] = list_slot(keys, tap.y);
  m[2] = list_slot(keys, tap.z);
  m[3] = list_slot(keys, tap.w);
  return m;
}

// The same for a list that stays as it is (a neighbour's keys that are not in it move nowhere).
mat4 list_match(vec4 keys, vec4 tap) {
  vec4 valid = vec4(greaterThan(tap, vec4(0.5)));
  return mat4(valid.x * vec4(equal(keys, vec4(tap.x))), valid.y * vec4(equal(keys, vec4(tap.y))),
              valid.z * vec4(equal(keys, vec4(tap.z))), valid.w * vec4(equal(keys, vec4(tap.w))));
}

ivec2 list_clamp(ivec2 p, ivec2 size) {
  return clamp(p, ivec2(0), size - 1);
}
