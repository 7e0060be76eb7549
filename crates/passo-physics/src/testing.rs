//! Helpers shared by the unit tests.

/// Numbers in `[0, 1)`, the same for the same seed (xorshift; a seed of
/// zero gives zeros).
pub(crate) fn uniform(mut seed: u64) -> impl FnMut() -> f32 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 40) as f32 / (1u64 << 24) as f32
    }
}
