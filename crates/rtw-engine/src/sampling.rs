//! Sampling designs: where in the unit cube the uniform axes of draw `i` of
//! a grid point fall.
//!
//! Every design point is computed from (seed, draw index) alone, in
//! O(dimensions × bits) time and O(1) memory per point, so threads, resume,
//! shards and merge treat a designed scan exactly like a random one, and a
//! 10⁶-sample design costs no more memory than a random one.
//!
//! - `random`: the ChaCha8 draws of [`crate::scan::sample`] (the default).
//! - `sobol`: the Sobol sequence (direction numbers of Joe & Kuo,
//!   "Constructing Sobol sequences with better two-dimensional projections",
//!   SIAM J. Sci. Comput. 30 (2008) 2635–2654, file new-joe-kuo-6.21201),
//!   point `i` in Gray-code order as scipy.stats.qmc.Sobol draws it,
//!   scrambled by a random linear matrix (Matoušek's LMS) and a digital shift
//!   drawn from the config's seed, as scipy scrambles it.
//! - `halton`: the radical inverse in the first primes, each digit position
//!   scrambled by its own random permutation of the digits.
//! - `lhs`: Latin hypercube of the grid point's `samples` draws: draw `i`
//!   sits in stratum `π_d(i)` of axis `d` (`π_d` a keyed bijection of
//!   `0..samples`, a Feistel network walked over the cycle), uniformly inside
//!   it.
//! - `grid`: the cell centres of a full factorial of `m` levels per uniform
//!   axis (`samples = m^D`), the last uniform axis fastest.
//! - `saltelli`: Saltelli's design for Sobol indices, ids in SALib's order
//!   for `calc_second_order = False`: base row `j` is Sobol point `j` in
//!   `2D` dimensions (`A_j` its first `D` coordinates, `B_j` the last `D`);
//!   its `D + 2` rows are `A_j, AB_j^1, …, AB_j^D, B_j`, where `AB_j^k` is
//!   `A_j` with coordinate `k` taken from `B_j`.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

/// The sampling design of a scan's uniform axes (`sampling = "…"`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Sampling {
    /// Independent uniform draws (ChaCha8, one stream per sample id).
    #[default]
    Random,
    /// Scrambled Sobol sequence.
    Sobol,
    /// Scrambled Halton sequence.
    Halton,
    /// Latin hypercube of the `samples` draws of each grid point.
    Lhs,
    /// Cell centres of a full factorial, `samples = m^D`.
    Grid,
    /// Saltelli's design for first-order and total Sobol indices:
    /// `samples` base rows of `D + 2` runs each.
    Saltelli,
    /// The points of the config's `[points]` table, row `i` its `i`-th
    /// ([`crate::config::points`]): a refinement round's, which depend on
    /// the rows before it rather than on the seed.
    Points,
}

impl Sampling {
    /// Every design drawn from the seed, as spelled in a config (not
    /// [`Sampling::Points`], whose points the config gives).
    pub const ALL: [Sampling; 6] = [
        Sampling::Random,
        Sampling::Sobol,
        Sampling::Halton,
        Sampling::Lhs,
        Sampling::Grid,
        Sampling::Saltelli,
    ];

    /// The name of the design in a config (`sampling = "sobol"`).
    pub fn name(self) -> &'static str {
        match self {
            Sampling::Random => "random",
            Sampling::Sobol => "sobol",
            Sampling::Halton => "halton",
            Sampling::Lhs => "lhs",
            Sampling::Grid => "grid",
            Sampling::Saltelli => "saltelli",
            Sampling::Points => "points",
        }
    }

    /// Rows per grid point for `samples` (base rows of a Saltelli design,
    /// draws otherwise) and `dims` uniform axes.
    pub fn rows_per_grid_point(self, samples: u64, dims: usize) -> Option<u64> {
        match self {
            Sampling::Saltelli => samples.checked_mul(dims as u64 + 2),
            _ => Some(samples),
        }
    }
}

/// Bits of a Sobol coordinate: a point is an integer below 2⁵² over 2⁵², so
/// every coordinate is an exact double and 2⁵² points are distinct.
const BITS: u32 = 52;

/// Joe & Kuo's new-joe-kuo-6.21201, dimensions 2 to 12: (s, a, m_1 … m_s).
/// Dimension 1 has every m_k = 1. Twelve dimensions cover a Saltelli design
/// of all six inputs (2D coordinates per base row).
const JOE_KUO: [(u32, u32, &[u64]); 11] = [
    (1, 0, &[1]),
    (2, 1, &[1, 3]),
    (3, 1, &[1, 3, 1]),
    (3, 2, &[1, 1, 1]),
    (4, 1, &[1, 1, 3, 3]),
    (4, 4, &[1, 3, 5, 13]),
    (5, 2, &[1, 1, 5, 5, 17]),
    (5, 4, &[1, 1, 5, 5, 5]),
    (5, 7, &[1, 1, 7, 11, 19]),
    (5, 11, &[1, 1, 5, 1, 1]),
    (5, 13, &[1, 1, 1, 3, 11]),
];

/// Most Sobol dimensions available.
pub const SOBOL_MAX_DIMS: usize = JOE_KUO.len() + 1;

/// The direction numbers `v_1 … v_BITS` of Sobol dimension `dim` (0-based),
/// `v_k = m_k 2^(BITS − k)`, by Joe & Kuo's recurrence.
fn direction_numbers(dim: usize) -> [u64; BITS as usize] {
    let mut v = [0u64; BITS as usize];
    if dim == 0 {
        for (k, vk) in v.iter_mut().enumerate() {
            *vk = 1 << (BITS - 1 - k as u32);
        }
        return v;
    }
    let (s, a, m) = JOE_KUO[dim - 1];
    let s = s as usize;
    for k in 0..s {
        v[k] = m[k] << (BITS - 1 - k as u32);
    }
    for k in s..BITS as usize {
        let mut x = v[k - s] ^ (v[k - s] >> s);
        for j in 1..s {
            if (a >> (s - 1 - j)) & 1 == 1 {
                x ^= v[k - j];
            }
        }
        v[k] = x;
    }
    v
}

/// The stream of the config's seed that draws a design's scrambling: far
/// from the sample ids' streams (`0 …`), so the random design's draws stay
/// what they were.
const SCRAMBLE_STREAM: u64 = u64::MAX - 0x5eed;

/// A scrambled (or plain) Sobol sequence in `dims` dimensions.
#[derive(Clone, Debug)]
pub struct Sobol {
    v: Vec<[u64; BITS as usize]>,
    shift: Vec<u64>,
}

impl Sobol {
    /// The unscrambled sequence (point 0 is the origin), as
    /// `scipy.stats.qmc.Sobol(d, scramble=False)`.
    pub fn plain(dims: usize) -> Self {
        assert!(dims <= SOBOL_MAX_DIMS, "{dims} Sobol dimensions");
        Self {
            v: (0..dims).map(direction_numbers).collect(),
            shift: vec![0; dims],
        }
    }

    /// The sequence scrambled with a random lower-triangular binary matrix
    /// and a random digital shift per dimension (LMS + digital shift),
    /// drawn from `seed`.
    pub fn scrambled(dims: usize, seed: u64) -> Self {
        let mut s = Self::plain(dims);
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(SCRAMBLE_STREAM);
        let low = (1u64 << BITS) - 1;
        for d in 0..dims {
            // Row r of L (r = 0 the most significant bit): 1 on the
            // diagonal, random above it in significance.
            let rows: Vec<u64> = (0..BITS)
                .map(|r| {
                    let diag = 1u64 << (BITS - 1 - r);
                    let above = if r == 0 {
                        0
                    } else {
                        ((1u64 << r) - 1) << (BITS - r)
                    };
                    (rng.random::<u64>() & above) | diag
                })
                .collect();
            for vk in s.v[d].iter_mut() {
                let mut out = 0u64;
                for (r, row) in rows.iter().enumerate() {
                    if (row & *vk).count_ones() % 2 == 1 {
                        out |= 1u64 << (BITS - 1 - r as u32);
                    }
                }
                *vk = out;
            }
            s.shift[d] = rng.random::<u64>() & low;
        }
        s
    }

    /// Point `i` (`i < 2⁵²`) into `out` (one coordinate per dimension).
    pub fn point(&self, i: u64, out: &mut [f64]) {
        let gray = i ^ (i >> 1);
        let scale = 1.0 / (1u64 << BITS) as f64;
        for (d, o) in out.iter_mut().enumerate() {
            let mut x = self.shift[d];
            let mut g = gray;
            while g != 0 {
                let b = g.trailing_zeros() as usize;
                x ^= self.v[d][b];
                g &= g - 1;
            }
            *o = x as f64 * scale;
        }
    }
}

/// The first primes: the Halton bases of the six axes.
const PRIMES: [u64; 6] = [2, 3, 5, 7, 11, 13];

/// A Halton sequence whose digits are scrambled by a random permutation per
/// dimension and digit position.
#[derive(Clone, Debug)]
pub struct Halton {
    /// Per dimension: its base and one digit permutation per position.
    perms: Vec<(u64, Vec<Vec<u64>>)>,
}

impl Halton {
    fn scrambled(dims: usize, seed: u64) -> Self {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(SCRAMBLE_STREAM);
        let perms = PRIMES[..dims]
            .iter()
            .map(|&b| {
                // Enough digits to reach a double's resolution.
                let positions = (53.0 / (b as f64).log2()).ceil() as usize;
                let per_position = (0..positions)
                    .map(|_| {
                        let mut p: Vec<u64> = (0..b).collect();
                        for k in (1..p.len()).rev() {
                            p.swap(k, rng.random_range(0..=k));
                        }
                        p
                    })
                    .collect();
                (b, per_position)
            })
            .collect();
        Self { perms }
    }

    fn point(&self, i: u64, out: &mut [f64]) {
        for (o, (b, perms)) in out.iter_mut().zip(&self.perms) {
            let (mut n, mut x, mut scale) = (i, 0.0, 1.0 / *b as f64);
            for p in perms {
                x += p[(n % b) as usize] as f64 * scale;
                n /= b;
                scale /= *b as f64;
            }
            *o = x.min(1.0 - f64::EPSILON / 2.0);
        }
    }
}

/// A keyed bijection of `0..n` (a four-round Feistel network on the
/// smallest even power of two ≥ n, walked along its cycle until it lands
/// below `n`): a random permutation computed one value at a time.
#[derive(Clone, Debug)]
pub struct Permutation {
    n: u64,
    half_bits: u32,
    keys: [u64; 4],
}

fn mix(mut z: u64) -> u64 {
    // splitmix64's finaliser.
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

impl Permutation {
    fn new(n: u64, rng: &mut ChaCha8Rng) -> Self {
        let bits = 64 - n.saturating_sub(1).leading_zeros();
        let half_bits = bits.div_ceil(2).max(1);
        Self {
            n,
            half_bits,
            keys: std::array::from_fn(|_| rng.random()),
        }
    }

    fn once(&self, x: u64) -> u64 {
        let mask = (1u64 << self.half_bits) - 1;
        let (mut l, mut r) = (x >> self.half_bits, x & mask);
        for k in self.keys {
            let f = mix(r ^ k) & mask;
            (l, r) = (r, l ^ f);
        }
        (l << self.half_bits) | r
    }

    fn apply(&self, i: u64) -> u64 {
        let mut x = self.once(i);
        while x >= self.n {
            x = self.once(x);
        }
        x
    }
}

/// The design of one scan: draw index (within a grid point) → unit-cube
/// point of its uniform axes.
#[derive(Clone, Debug)]
pub enum Design {
    /// A scrambled Sobol sequence.
    Sobol(Sobol),
    /// A scrambled Halton sequence.
    Halton(Halton),
    /// One stratum permutation per axis, and the number of strata.
    Lhs(Vec<Permutation>, u64),
    /// Levels per axis.
    Grid(u64),
    /// The 2D-dimensional Sobol sequence of the base rows, and D.
    Saltelli(Sobol, usize),
}

/// Why a design cannot be made for `samples` draws in `dims` uniform axes:
/// the message names the key and what is valid.
pub(crate) fn check(sampling: Sampling, samples: u64, dims: usize) -> Result<(), String> {
    let name = sampling.name();
    if sampling != Sampling::Random && dims == 0 {
        return Err(format!(
            "sampling: \"{name}\" needs at least one uniform axis in [params] (every axis is fixed or a grid)"
        ));
    }
    match sampling {
        Sampling::Saltelli if 2 * dims > SOBOL_MAX_DIMS => Err(format!(
            "sampling: \"saltelli\" with {dims} uniform axes needs {} Sobol dimensions: at most {SOBOL_MAX_DIMS}",
            2 * dims
        )),
        Sampling::Grid => {
            let m = grid_levels(samples, dims);
            if m.checked_pow(dims as u32) == Some(samples) {
                Ok(())
            } else {
                let up = (m + 1).saturating_pow(dims as u32);
                Err(format!(
                    "samples: {samples} is invalid for sampling = \"grid\" with {dims} uniform axes: \
                     must be m^{dims} (levels per axis m), e.g. {} or {up}",
                    m.pow(dims as u32)
                ))
            }
        }
        _ => Ok(()),
    }
}

/// The largest `m` with `m^dims ≤ samples`.
fn grid_levels(samples: u64, dims: usize) -> u64 {
    let mut m = (samples as f64).powf(1.0 / dims as f64).round() as u64;
    while m > 1 && m.checked_pow(dims as u32).is_none_or(|p| p > samples) {
        m -= 1;
    }
    while (m + 1)
        .checked_pow(dims as u32)
        .is_some_and(|p| p <= samples)
    {
        m += 1;
    }
    m.max(1)
}

impl Design {
    /// The design of a validated config; `None` for random sampling.
    pub fn new(sampling: Sampling, seed: u64, samples: u64, dims: usize) -> Option<Self> {
        Some(match sampling {
            Sampling::Random | Sampling::Points => return None,
            Sampling::Sobol => Design::Sobol(Sobol::scrambled(dims, seed)),
            Sampling::Halton => Design::Halton(Halton::scrambled(dims, seed)),
            Sampling::Lhs => {
                let mut rng = ChaCha8Rng::seed_from_u64(seed);
                rng.set_stream(SCRAMBLE_STREAM);
                let perms = (0..dims).map(|_| Permutation::new(samples, &mut rng));
                Design::Lhs(perms.collect(), samples)
            }
            Sampling::Grid => Design::Grid(grid_levels(samples, dims)),
            Sampling::Saltelli => Design::Saltelli(Sobol::scrambled(2 * dims, seed), dims),
        })
    }

    /// The unit-cube point of draw `draw` into `out` (one coordinate per
    /// uniform axis); `u` are the draw's own random numbers (the random
    /// design's), used by the Latin hypercube inside its strata.
    pub fn point(&self, draw: u64, u: &[f64], out: &mut [f64]) {
        match self {
            Design::Sobol(s) => s.point(draw, out),
            Design::Halton(h) => h.point(draw, out),
            Design::Lhs(perms, n) => {
                for ((o, p), u) in out.iter_mut().zip(perms).zip(u) {
                    *o = ((p.apply(draw) as f64 + u) / *n as f64).min(1.0);
                }
            }
            Design::Grid(m) => {
                let mut rest = draw;
                for o in out.iter_mut().rev() {
                    *o = ((rest % m) as f64 + 0.5) / *m as f64;
                    rest /= m;
                }
            }
            Design::Saltelli(s, dims) => {
                let d = *dims;
                let (j, k) = (draw / (d as u64 + 2), (draw % (d as u64 + 2)) as usize);
                let mut ab = [0.0; 2 * SOBOL_MAX_DIMS];
                s.point(j, &mut ab[..2 * d]);
                let (a, b) = ab.split_at(d);
                out.copy_from_slice(if k == d + 1 { &b[..d] } else { a });
                if (1..=d).contains(&k) {
                    out[k - 1] = b[k - 1];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn points(s: &Sobol, n: u64, d: usize) -> Vec<Vec<f64>> {
        (0..n)
            .map(|i| {
                let mut p = vec![0.0; d];
                s.point(i, &mut p);
                p
            })
            .collect()
    }

    #[test]
    fn plain_sobol_starts_as_the_textbook_sequence() {
        // Dimension 1 is the van der Corput sequence in Gray-code order.
        let p = points(&Sobol::plain(2), 4, 2);
        assert_eq!(p[0], vec![0.0, 0.0]);
        assert_eq!(p[1], vec![0.5, 0.5]);
        assert_eq!(p[2], vec![0.75, 0.25]);
        assert_eq!(p[3], vec![0.25, 0.75]);
    }

    #[test]
    fn every_sobol_design_is_a_net_each_axis_stratified() {
        // 2^k points of a (scrambled) Sobol sequence put one point in each
        // of the 2^k intervals of every axis.
        for s in [Sobol::plain(12), Sobol::scrambled(12, 7)] {
            let p = points(&s, 256, 12);
            for d in 0..12 {
                let mut seen = [false; 256];
                for q in &p {
                    seen[(q[d] * 256.0) as usize] = true;
                }
                assert!(seen.iter().all(|x| *x), "dimension {d}");
            }
        }
        // Scrambling depends on the seed.
        let (a, b) = (Sobol::scrambled(3, 1), Sobol::scrambled(3, 2));
        assert_ne!(points(&a, 4, 3), points(&b, 4, 3));
    }

    #[test]
    fn latin_hypercube_fills_each_stratum_once() {
        for n in [1u64, 2, 7, 100, 1000] {
            let d = Design::new(Sampling::Lhs, 5, n, 3).unwrap();
            let mut seen = vec![[false; 3]; n as usize];
            for i in 0..n {
                let mut p = [0.0; 3];
                d.point(i, &[0.5; 3], &mut p);
                for (a, x) in p.iter().enumerate() {
                    let s = (x * n as f64) as usize;
                    assert!(!seen[s][a], "n {n} axis {a} stratum {s} twice");
                    seen[s][a] = true;
                }
            }
        }
    }

    #[test]
    fn halton_and_grid_points_lie_in_the_cube_and_differ() {
        let h = Design::new(Sampling::Halton, 3, 100, 6).unwrap();
        let mut all = Vec::new();
        for i in 0..100 {
            let mut p = [0.0; 6];
            h.point(i, &[0.0; 6], &mut p);
            assert!(p.iter().all(|x| (0.0..1.0).contains(x)));
            all.push(p);
        }
        all.sort_by(|a, b| a.partial_cmp(b).unwrap());
        all.dedup();
        assert_eq!(all.len(), 100);
        let g = Design::new(Sampling::Grid, 0, 9, 2).unwrap();
        let mut p = [0.0; 2];
        g.point(5, &[0.0; 2], &mut p);
        assert_eq!(p, [1.5 / 3.0, 2.5 / 3.0]);
        assert!(
            check(Sampling::Grid, 10, 2)
                .unwrap_err()
                .contains("e.g. 9 or 16")
        );
        assert!(check(Sampling::Grid, 1000, 3).is_ok());
    }

    #[test]
    fn saltelli_rows_follow_salib_order() {
        let d = 3;
        let design = Design::new(Sampling::Saltelli, 11, 4, d).unwrap();
        let s = Sobol::scrambled(2 * d, 11);
        for j in 0..4u64 {
            let mut base = [0.0; 6];
            s.point(j, &mut base);
            let row = |k: u64| {
                let mut p = [0.0; 3];
                design.point(j * 5 + k, &[], &mut p);
                p
            };
            assert_eq!(row(0), [base[0], base[1], base[2]]);
            assert_eq!(row(1), [base[3], base[1], base[2]]);
            assert_eq!(row(2), [base[0], base[4], base[2]]);
            assert_eq!(row(3), [base[0], base[1], base[5]]);
            assert_eq!(row(4), [base[3], base[4], base[5]]);
        }
    }
}
