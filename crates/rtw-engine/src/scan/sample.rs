//! Sample `i` of a scan → its [`Params`], reproducibly.
//!
//! Rows are numbered `sample_id = grid_point × samples + draw`. The grid
//! point is the mixed-radix index over the grid axes in [`Param::ALL`] order
//! (the last grid axis varies fastest). The uniform axes of sample `i` come
//! from ChaCha8 seeded with the scan's seed on stream `i`: one `u ∈ [0, 1)`
//! is drawn for each of the six parameters in order (whether it is uniform or
//! not), so a value depends only on (seed, i, its own range). Any subset,
//! shard, resume or thread count reproduces the same rows.
//!
//! With another `sampling` design ([`crate::sampling`]), the uniform axes of
//! draw `d = i mod rows_per_grid_point` are instead the coordinates of the
//! design's point `d` (the uniform axes in [`Param::ALL`] order), mapped to
//! `lo + x (hi − lo)`; the grid point is `i / rows_per_grid_point`.
//!
//! [`Param::ALL`]: rtw_model::Param::ALL

use crate::config::ScanConfig;
use crate::config::axis::{Axis, linspace_point};
use crate::sampling::Design;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rtw_model::Param;
use rtw_model::Params;

/// How one axis produces its value.
#[derive(Clone, Debug)]
enum Source {
    Fixed(f64),
    Uniform(f64, f64),
    Grid(Vec<f64>),
    /// A linspace axis, its points computed one at a time (it may have more
    /// than memory holds).
    Linspace(f64, f64, u64),
}

/// Maps sample ids to parameters for one config.
#[derive(Clone, Debug)]
pub struct Sampler {
    seed: u64,
    /// Rows per grid point (`samples`, times D + 2 for a Saltelli design).
    per_grid_point: u64,
    total: u64,
    sources: Vec<Source>,
    design: Option<Design>,
    /// The config's stored points (`sampling = "points"`): row `id` is
    /// `points[id]`.
    points: Option<std::sync::Arc<[Params]>>,
}

impl Sampler {
    /// Builds the sampler of a validated config.
    pub fn new(cfg: &ScanConfig) -> Self {
        let sources = cfg
            .params
            .iter()
            .map(|a| match a {
                Axis::Fixed(v) => Source::Fixed(*v),
                Axis::Uniform { lo, hi } => Source::Uniform(*lo, *hi),
                Axis::Linspace { lo, hi, n } => Source::Linspace(*lo, *hi, *n),
                Axis::List(points) => Source::Grid(points.clone()),
            })
            .collect();
        Self {
            seed: cfg.seed,
            per_grid_point: cfg
                .rows_per_grid_point()
                .expect("validated config has a row count"),
            total: cfg.total_rows().expect("validated config has a row count"),
            design: Design::new(cfg.sampling, cfg.seed, cfg.samples, cfg.uniform_axes()),
            sources,
            points: cfg.points.clone(),
        }
    }

    /// Number of rows of the scan.
    pub fn total(&self) -> u64 {
        self.total
    }

    /// The parameters of sample `id` (`id < total`).
    pub fn params(&self, id: u64) -> Params {
        assert!(id < self.total, "sample_id {id} >= {}", self.total);
        if let Some(points) = &self.points {
            return points[id as usize];
        }
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        rng.set_stream(id);
        let mut u: [f64; 6] = std::array::from_fn(|_| rng.random::<f64>());
        if let Some(design) = &self.design {
            let uniform: Vec<usize> = (0..6)
                .filter(|i| matches!(self.sources[*i], Source::Uniform(..)))
                .collect();
            let own: Vec<f64> = uniform.iter().map(|i| u[*i]).collect();
            let mut x = [0.0; 6];
            design.point(id % self.per_grid_point, &own, &mut x[..uniform.len()]);
            for (k, i) in uniform.iter().enumerate() {
                u[*i] = x[k];
            }
        }
        // Mixed-radix decomposition of the grid point, last axis fastest.
        let mut grid = id / self.per_grid_point;
        let mut p = rtw_model::Params::fig7a();
        for (i, source) in self.sources.iter().enumerate().rev() {
            let v = match source {
                Source::Fixed(v) => *v,
                Source::Uniform(lo, hi) => (lo + u[i] * (hi - lo)).clamp(*lo, *hi),
                Source::Grid(points) => {
                    let n = points.len() as u64;
                    let v = points[(grid % n) as usize];
                    grid /= n;
                    v
                }
                Source::Linspace(lo, hi, n) => {
                    let v = linspace_point(*lo, *hi, *n, grid % n);
                    grid /= n;
                    v
                }
            };
            p[Param::ALL[i]] = v;
        }
        p
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::parse;

    fn sampler(text: &str) -> Sampler {
        Sampler::new(&parse(text).unwrap())
    }

    const GRID: &str = r#"
seed = 3
samples = 2
[params]
length = [0.7, 0.8, 0.9]
rho = { uniform = [1, 5] }
alpha = 0.125
fn = 3.0
zeta = 0.05
phi = { linspace = [0.05, 0.2, 4] }
"#;

    #[test]
    fn grid_product_order_and_count() {
        let s = sampler(GRID);
        assert_eq!(s.total(), 3 * 4 * 2);
        let p: Vec<Params> = (0..s.total()).map(|i| s.params(i)).collect();
        // Rows 0, 1: first grid point (length 0.7, phi 0.05), two draws.
        assert_eq!((p[0].length, p[0].phi), (0.7, 0.05));
        assert_eq!((p[1].length, p[1].phi), (0.7, 0.05));
        assert_ne!(p[0].rho, p[1].rho);
        // phi varies fastest, length slowest.
        assert_eq!((p[2].length, p[2].phi), (0.7, 0.1));
        assert_eq!((p[7].length, p[7].phi), (0.7, 0.2));
        assert_eq!((p[8].length, p[8].phi), (0.8, 0.05));
        assert_eq!((p[23].length, p[23].phi), (0.9, 0.2));
        for q in &p {
            assert!((1.0..=5.0).contains(&q.rho));
            assert_eq!((q.alpha, q.f_n, q.zeta), (0.125, 3.0, 0.05));
            q.validate().unwrap();
        }
    }

    #[test]
    fn depends_only_on_seed_and_id() {
        let a = sampler(GRID);
        let b = sampler(GRID);
        for i in [17, 3, 0, 23, 9] {
            assert_eq!(a.params(i), b.params(i));
        }
        // A different seed changes the draws, not the grid.
        let c = sampler(&GRID.replace("seed = 3", "seed = 4"));
        assert_ne!(a.params(5).rho, c.params(5).rho);
        assert_eq!(a.params(5).phi, c.params(5).phi);
        // Adding samples keeps the draws of the ones that stay at the same id
        // only within a grid point's block; with one grid point ids are stable.
        let one = "seed = 9\nsamples = 5\n[params]\nlength = 0.8\nrho = { uniform = [1, 5] }\nalpha = { uniform = [0, 0.4] }\nfn = 3\nzeta = 0.05\nphi = 0.1\n";
        let more = one.replace("samples = 5", "samples = 50");
        let (s5, s50) = (sampler(one), sampler(&more));
        for i in 0..5 {
            assert_eq!(s5.params(i), s50.params(i));
        }
    }

    #[test]
    fn uniform_values_cover_the_range() {
        let s = sampler(
            "seed = 1\nsamples = 2000\n[params]\nlength = 0.8\nrho = { uniform = [1, 5] }\nalpha = { uniform = [0, 0.4] }\nfn = 3\nzeta = 0.05\nphi = 0.1\n",
        );
        let rho: Vec<f64> = (0..2000).map(|i| s.params(i).rho).collect();
        let mean = rho.iter().sum::<f64>() / 2000.0;
        assert!((mean - 3.0).abs() < 0.1, "mean {mean}");
        assert!(rho.iter().any(|&r| r < 1.1) && rho.iter().any(|&r| r > 4.9));
        // Draws of different parameters are not the same numbers.
        let p = s.params(0);
        assert_ne!((p.rho - 1.0) / 4.0, p.alpha / 0.4);
    }
}
