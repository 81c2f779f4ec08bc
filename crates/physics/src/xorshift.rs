//! xorshift64 (Marsaglia, J. Stat. Softw. 8(14), 2003; shifts 13, 7, 17): a tiny seeded
//! generator for fixed pseudo-random inputs that must be the same on every machine (inverse
//! iteration's start vectors, the bench's disk probe, test data). Not for statistics.

/// Advance `state` (never 0) and return it.
pub fn next(state: &mut u64) -> u64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    *state
}

/// `n` pseudo-random bytes from `seed` (never 0): the top byte of each step, as uniform as
/// the generator (the low bits of xorshift are its weakest).
pub fn bytes(seed: u64, n: usize) -> Vec<u8> {
    let mut state = seed;
    (0..n).map(|_| (next(&mut state) >> 56) as u8).collect()
}
