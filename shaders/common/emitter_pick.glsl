// The alias table's draw over the scene's emitters (shared/emitters.h): the includer declares
// `emitters[]` (Emitter, std430) and passes its valid count (> 0).
uint emitterPick(uint h, uint count) {
  uint slot = tlAliasSlot(h, count);
  return tlAliasKeepsSlot(h, emitters[slot].p0.w) ? slot : emitters[slot].ids.z;
}
