//! What the fuzz harnesses (tests/fuzz_fmi/, tests/fuzz_deserialize.rs,
//! tests/fuzz_capi.rs) share: a seeded xorshift64*
//! generator, the interesting values it draws, the time budget, and the mutations of
//! serialized FMU states.
//!
//! ```text
//! WO_FUZZ_SECONDS=600 WO_FUZZ_SEED=12345 cargo test --release --test fuzz_fmi --test fuzz_deserialize --test fuzz_capi -- --nocapture
//! ```
//!
//! runs each harness for 10 minutes from seed 12345 (default: 3 seconds each, seed fixed
//! per harness, so that the test command is reproducible). A failure prints the seed and
//! the iteration; the same seed replays the same calls (up to the time budget).
#![allow(dead_code)]

use std::time::{Duration, Instant};
use wound_opening::fmi::fmi2::types::fmi2CallbackFunctions;

/// Callbacks without a logger: a Rust test cannot define the variadic C logger (the C
/// programs in tests/c check the logged messages).
pub const NULL_CALLBACKS: fmi2CallbackFunctions = fmi2CallbackFunctions::NONE;

/// xorshift64* (Vigna, "An experimental exploration of Marsaglia's xorshift generators").
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self((seed ^ 0x9E37_79B9_7F4A_7C15).max(1))
    }

    pub fn next_u64(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// Uniform in `0..n` (`n > 0`).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    pub fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }

    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    pub fn pick<T: Copy>(&mut self, xs: &[T]) -> T {
        xs[self.below(xs.len())]
    }

    /// A double worth trying: special values, boundaries of the model's ranges, small
    /// ordinary values, any magnitude, or any bit pattern.
    pub fn real(&mut self) -> f64 {
        const SPECIAL: [f64; 18] = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.5,
            2.0,
            10.0,
            1.0 + f64::EPSILON,
            1e-300,
            -1e-300,
            1e300,
            -1e300,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MIN_POSITIVE,
            f64::MAX,
            5e-324,
        ];
        match self.below(4) {
            0 => self.pick(&SPECIAL),
            1 => 4.0 * self.unit() - 1.0,
            2 => (self.unit() - 0.5).signum() * 10f64.powf(80.0 * self.unit() - 40.0),
            _ => f64::from_bits(self.next_u64()),
        }
    }
}

/// How long a harness runs and from which seed (`WO_FUZZ_SECONDS`, `WO_FUZZ_SEED`).
pub struct Budget {
    pub seed: u64,
    end: Instant,
}

impl Budget {
    pub fn from_env(default_seed: u64) -> Self {
        let seconds: f64 =
            std::env::var("WO_FUZZ_SECONDS").ok().and_then(|s| s.parse().ok()).unwrap_or(3.0);
        let seed =
            std::env::var("WO_FUZZ_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or(default_seed);
        Self { seed, end: Instant::now() + Duration::from_secs_f64(seconds.max(0.0)) }
    }

    pub fn left(&self) -> bool {
        Instant::now() < self.end
    }
}

/// Bytes for `fmi2DeSerializeFMUstate`: random, or a seen state truncated, bit-flipped,
/// overwritten, lengthened, or mutated in its header or payload and re-sealed with a valid
/// CRC-32 (so that the decoder gets past the checksum to the field checks). Also says
/// whether the bytes were re-sealed.
pub fn mutated(rng: &mut Rng, blobs: &[Vec<u8>]) -> (Vec<u8>, bool) {
    if blobs.is_empty() || rng.chance(0.15) {
        return ((0..rng.below(200)).map(|_| rng.next_u64() as u8).collect(), false);
    }
    let mut b = blobs[rng.below(blobs.len())].clone();
    let reseal = rng.chance(0.6);
    for _ in 0..1 + rng.below(3) {
        let n = b.len();
        match rng.below(7) {
            0 => b.truncate(rng.below(n + 1)),
            1 => b.extend((0..1 + rng.below(16)).map(|_| rng.next_u64() as u8)),
            2 | 3 if n > 0 => b[rng.below(n)] ^= 1 << rng.below(8),
            4 if n > 0 => b[rng.below(n)] = rng.next_u64() as u8,
            5 if n >= 24 => {
                // A field of the payload (past the 16-byte header) set to a special double.
                let at = 16 + rng.below(n - 23);
                b[at..at + 8].copy_from_slice(&rng.real().to_le_bytes());
            }
            _ if n >= 16 => {
                // The version or the payload length.
                let at = rng.pick(&[8usize, 12]);
                b[at..at + 4].copy_from_slice(&(rng.next_u64() as u32 % 4096).to_le_bytes());
            }
            _ => {}
        }
    }
    let resealed = reseal && b.len() >= 20;
    if resealed {
        reseal_crc(&mut b);
    }
    (b, resealed)
}

/// Make the trailing CRC-32 of a serialized state valid again after a change.
pub fn reseal_crc(b: &mut [u8]) {
    let n = b.len() - 4;
    let crc = crc32fast::hash(&b[..n]);
    b[n..].copy_from_slice(&crc.to_le_bytes());
}

/// Offsets of the mesh degree and element count (u32 LE) in a serialized WoundOpening
/// state: the envelope (src/fmi/common/serialized.rs, 55 bytes with the model name) then six
/// f64 of parameters and scales (src/models/wound/codec.rs).
pub const MESH_FIELDS: std::ops::Range<usize> = 103..111;
