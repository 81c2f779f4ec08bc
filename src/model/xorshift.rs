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
