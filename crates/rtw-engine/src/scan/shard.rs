//! Shards: one scan split into N contiguous id ranges that run anywhere
//! (Slurm array tasks, several machines) and merge back into exactly the
//! single-machine file.
//!
//! Since a row depends only on (seed, sample_id), shard K of N computes the
//! same rows as a whole run does for its ids. `rtw-scan run CONFIG --shard K/N`
//! writes them to `DIR/part-K.parquet` ([`crate::run`] does the work, with
//! its chunks, resume and Ctrl-C handling); [`merge_parts`] checks that the
//! parts in a directory are all the shards of one scan (one config hash, one
//! version, one shard count, every shard present, `sample_id`s exactly
//! 0..n−1 once each) and concatenates them into `DIR/samples.parquet`.

use crate::config::{self, ScanConfig};
use crate::files;
use crate::io::metadata::{
    self, META_CONFIG, META_CONFIG_HASH, META_SHARD, META_SHARDS, META_TOTAL_ROWS, META_VERSION,
    META_WALL_TIME, kv,
};
use crate::io::parquet::{self, MAX_ROW_GROUP_ROWS};
use crate::io::scan_files::concat_scan_files;
use crate::scan::lock::Lock;
use anyhow::{Context, Result, anyhow, bail};
use std::collections::BTreeMap;
use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// Shard `index` (0-based) of `count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// K, the shard's number (0-based).
    pub index: u64,
    /// N, the number of shards.
    pub count: u64,
}

impl FromStr for Shard {
    type Err = String;

    /// `K/N` with 0 ≤ K < N.
    fn from_str(s: &str) -> Result<Self, String> {
        let bad = |why: &str| format!("`{s}` is invalid: {why}");
        let (k, n) = s
            .split_once('/')
            .ok_or_else(|| bad("must be K/N (shard K of N, 0 <= K < N), e.g. 0/4"))?;
        let index: u64 = k
            .trim()
            .parse()
            .map_err(|_| bad("K must be an integer >= 0"))?;
        let count: u64 = n
            .trim()
            .parse()
            .map_err(|_| bad("N must be an integer >= 1"))?;
        if count == 0 {
            return Err(bad("N must be an integer >= 1"));
        }
        if index >= count {
            return Err(bad(&format!(
                "K must be in 0..={} (shards are numbered from 0)",
                count - 1
            )));
        }
        Ok(Self { index, count })
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl Shard {
    /// The sample ids of this shard among `total`: the contiguous range
    /// `⌊K·total/N⌋..⌊(K+1)·total/N⌋` (shard sizes differ by at most one).
    pub(crate) fn ids(&self, total: u64) -> Result<Range<u64>> {
        if self.count > total {
            bail!(
                "--shard {self}: N = {} is more than the scan's {total} samples (each shard needs at least one)",
                self.count
            );
        }
        // u128: K·total cannot overflow.
        let at = |k: u64| (u128::from(k) * u128::from(total) / u128::from(self.count)) as u64;
        Ok(at(self.index)..at(self.index + 1))
    }

    /// `part-K.parquet`.
    pub(crate) fn part_name(&self) -> String {
        part_name(self.index)
    }

    /// `.partial-K`: the shard's unfinished chunks.
    pub(crate) fn partial_name(&self) -> String {
        format!(".partial-{}", self.index)
    }
}

fn part_name(k: u64) -> String {
    format!("part-{k}.parquet")
}

/// `K` of a file named `part-K.parquet`.
pub(crate) fn part_index(name: &str) -> Option<u64> {
    let k = name.strip_prefix("part-")?.strip_suffix(".parquet")?;
    if k.is_empty() || !k.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    // Only the name `run` writes: `part-01.parquet` is not shard 1's part.
    let k: u64 = k.parse().ok()?;
    (name == part_name(k)).then_some(k)
}

/// `K` of a file named like a part with leading zeros (`part-01.parquet`),
/// a name `run` never writes.
fn padded_part_index(name: &str) -> Option<u64> {
    let k = name.strip_prefix("part-")?.strip_suffix(".parquet")?;
    if k.len() < 2 || !k.starts_with('0') || !k.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    Some(k.trim_start_matches('0').parse().unwrap_or(0))
}

/// What a part file's metadata says.
struct Part {
    path: PathBuf,
    shard: Shard,
    config: String,
    hash: String,
    version: String,
    total_rows: u64,
}

impl Part {
    /// Its file's name on disk.
    fn name(&self) -> String {
        self.path.file_name().map_or_else(
            || self.shard.part_name(),
            |n| n.to_string_lossy().into_owned(),
        )
    }
}

fn read_part(path: &Path, k: u64) -> Result<Part> {
    let input = parquet::open(path, 1)?;
    // The name on disk, which every message about the file uses.
    let name = path
        .file_name()
        .map_or_else(|| part_name(k), |n| n.to_string_lossy().into_owned());
    let get = |key: &str| {
        input.metadata.get(key).cloned().ok_or_else(|| {
            anyhow!("{name} has no `{key}` metadata: not written by `rtw-scan run --shard`")
        })
    };
    let shard: Shard = get(META_SHARD)?
        .parse()
        .map_err(|e| anyhow!("{name}: `{META_SHARD}` {e}"))?;
    if shard.index != k {
        bail!("{name} holds shard {shard}, not shard {k}: was it renamed?");
    }
    let config = get(META_CONFIG)?;
    let hash = get(META_CONFIG_HASH)?;
    if config::config_hash(&config) != hash {
        bail!(
            "{name}: its config does not hash to its `{META_CONFIG_HASH}` {hash}: the file was altered"
        );
    }
    let total_rows = get(META_TOTAL_ROWS)?
        .parse()
        .map_err(|_| anyhow!("{name}: `{META_TOTAL_ROWS}` is not a count"))?;
    Ok(Part {
        path: path.to_path_buf(),
        shard,
        config,
        hash,
        version: get(META_VERSION)?,
        total_rows,
    })
}

/// A short description of a part's config, for mismatch messages.
fn describe(p: &Part) -> String {
    match config::parse(&p.config) {
        Ok(c) => format!(
            "config hash {} (seed {}, {} samples)",
            p.hash, c.seed, p.total_rows
        ),
        Err(_) => format!("config hash {}", p.hash),
    }
}

/// What a merge of shards did (`studies::scan::merge`).
#[derive(Debug)]
pub struct Merged {
    /// The merged scan file, `DIR/samples.parquet`.
    pub samples: PathBuf,
    /// The shards joined.
    pub shards: u64,
    /// The rows of the merged scan.
    pub rows: u64,
}

/// The parts of a complete shard set, checked by [`complete_parts`].
pub(crate) struct ShardSet {
    /// `part-0.parquet` … `part-(N-1).parquet`, in shard order.
    pub(crate) paths: Vec<PathBuf>,
    /// The scan's config, as the parts store it.
    pub(crate) config: ScanConfig,
    /// The rows of the whole scan.
    pub(crate) total: u64,
    /// N, the shard count.
    pub(crate) shards: u64,
    first: Part,
}

/// Checks that the `part-K.parquet` files in `dir` are every shard of one
/// scan (one config, version and shard count, none missing, none beyond N),
/// from their metadata; their rows are checked by whoever reads them
/// ([`merge_parts`], `analysis::scan_table`).
pub(crate) fn complete_parts(dir: &Path) -> Result<ShardSet> {
    let entries = std::fs::read_dir(dir)
        .with_context(|| format!("cannot read directory {}", dir.display()))?;
    let mut found = BTreeMap::new();
    for entry in entries {
        let entry = entry?;
        let name = entry.file_name().to_string_lossy().into_owned();
        if let Some(k) = part_index(&name) {
            found.insert(k, entry.path());
        } else if let Some(k) = padded_part_index(&name) {
            // `part-01.parquet` would shadow `part-1.parquet`, and a
            // message about shard 1 would name the good file.
            bail!(
                "{} in {}: not a part rtw-scan wrote (the part of shard {k} is named with no \
                 leading zero): move {} out of {} and merge again",
                name,
                dir.display(),
                name,
                dir.display()
            );
        }
    }
    if found.is_empty() {
        bail!(
            "no part-K.parquet files in {}: run `rtw-scan run CONFIG --shard K/N --out {}` for K = 0..N-1 first",
            dir.display(),
            dir.display()
        );
    }
    let parts: Vec<Part> = found
        .iter()
        .map(|(k, path)| read_part(path, *k).with_context(|| format!("in {}", dir.display())))
        .collect::<Result<_>>()?;

    let first = &parts[0];
    for p in &parts[1..] {
        if p.hash != first.hash {
            bail!(
                "the parts come from different configs: {} has {}, {} has {}; merge only the parts of one scan",
                first.name(),
                describe(first),
                p.name(),
                describe(p)
            );
        }
        metadata::refuse_mixed_versions(
            "the parts",
            (&first.name(), &first.version),
            (&p.name(), &p.version),
            "rerun one of them",
        )?;
        if p.shard.count != first.shard.count {
            bail!(
                "the parts split the scan differently: {} is shard {}, {} is shard {}",
                first.name(),
                first.shard,
                p.name(),
                p.shard
            );
        }
    }

    let cfg: ScanConfig = config::parse(&first.config)
        .with_context(|| format!("the config stored in {}", first.path.display()))?;
    let total = cfg.total_rows()?;
    if total != first.total_rows {
        bail!(
            "{}: `{META_TOTAL_ROWS}` is {} but its config has {total} rows",
            first.name(),
            first.total_rows
        );
    }
    let n = first.shard.count;
    // Counted, not listed: a 10^12-way split with one part present has
    // 10^12 - 1 missing. The first few are named, then how many more.
    let present = found.range(..n).count() as u64;
    let missing = n - present;
    if missing > 0 {
        const NAMED: usize = 5;
        let named: Vec<String> = (0..n)
            .filter(|k| !found.contains_key(k))
            .take(NAMED)
            .map(|k| {
                let shard = Shard { index: k, count: n };
                let ids = shard.ids(total).expect("N <= total for a written part");
                let unfinished = if dir.join(shard.partial_name()).exists() {
                    format!(
                        ", unfinished: {} holds its finished chunks",
                        shard.partial_name()
                    )
                } else {
                    String::new()
                };
                format!(
                    "{} (shard {shard}, sample_ids {}..{}{unfinished})",
                    shard.part_name(),
                    ids.start,
                    ids.end - 1
                )
            })
            .collect();
        let more = match missing - named.len() as u64 {
            0 => String::new(),
            m => format!("; and {m} more"),
        };
        bail!(
            "{missing} of {n} shards missing in {}: {}{more}; run each with `rtw-scan run CONFIG --shard K/{n} --out {} --resume`",
            dir.display(),
            named.join("; "),
            dir.display()
        );
    }
    if let Some(extra) = found.keys().find(|k| **k >= n) {
        bail!(
            "{} is beyond the {n} shards of {}",
            part_name(*extra),
            first.name()
        );
    }

    let paths = parts.iter().map(|p| p.path.clone()).collect();
    Ok(ShardSet {
        paths,
        config: cfg,
        total,
        shards: n,
        first: parts.into_iter().next().expect("at least one part"),
    })
}

/// Checks the `part-K.parquet` files in `dir` ([`complete_parts`]) and
/// concatenates them into `dir/samples.parquet`. Refuses, naming the files,
/// when the parts come from different configs, versions or shard counts,
/// when a shard is missing, or when their `sample_id`s are not exactly
/// 0..n−1 once each, when a part is corrupt, or (unless `force`) when
/// `dir/samples.parquet` holds another scan; nothing is written then.
pub(crate) fn merge_parts(dir: &Path, force: bool) -> Result<Merged> {
    let set = complete_parts(dir)?;
    let (first, cfg, total, n) = (&set.first, set.config, set.total, set.shards);
    let samples = dir.join("samples.parquet");
    let _lock = Lock::acquire(&samples, &format!("writing {}", samples.display()))?;
    if !force && samples.exists() {
        let theirs = parquet::open(&samples, 1).map(|i| i.metadata);
        if theirs
            .as_ref()
            .map_or(true, |m| m.get(META_CONFIG_HASH) != Some(&first.hash))
        {
            bail!(
                "{} holds another scan: {}; the parts are {}. Merge into another directory, or \
                 pass --force to replace it",
                samples.display(),
                theirs.map_or_else(
                    |e| format!("not a readable scan ({e:#})"),
                    |m| metadata::scan_label_of(&m)
                ),
                describe(first)
            );
        }
    }
    for f in ["samples.parquet", "summary.json", "summary.md"] {
        files::remove_stray_temps(&dir.join(f))?;
    }
    let mut metadata = metadata::scan_metadata(&cfg);
    for kv in &mut metadata {
        // The parts' version, which need not be the merging binary's.
        if kv.key == META_VERSION {
            kv.value = Some(first.version.clone());
        }
    }
    metadata.push(kv(META_SHARDS, n.to_string()));
    concat_scan_files(
        &set.paths,
        0..total,
        &samples,
        MAX_ROW_GROUP_ROWS,
        metadata,
        META_WALL_TIME,
    )
    .with_context(|| format!("merging the parts in {}", dir.display()))?;
    Ok(Merged {
        samples,
        shards: n,
        rows: total,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_and_print() {
        let s: Shard = "2/4".parse().unwrap();
        assert_eq!(s, Shard { index: 2, count: 4 });
        assert_eq!(s.to_string(), "2/4");
        for (bad, why) in [
            ("4/4", "K must be in 0..=3"),
            ("0/0", "N must be an integer >= 1"),
            ("1", "must be K/N"),
            ("-1/4", "K must be an integer >= 0"),
            ("a/4", "K must be an integer >= 0"),
            ("1/x", "N must be an integer >= 1"),
        ] {
            let e = bad.parse::<Shard>().unwrap_err();
            assert!(e.contains(why) && e.contains(bad), "{bad}: {e}");
        }
    }

    #[test]
    fn shards_tile_the_ids_exactly() {
        for total in [1u64, 6, 7, 37, 1000, 1001] {
            for n in 1..=total.min(13) {
                let mut next = 0;
                for k in 0..n {
                    let ids = Shard { index: k, count: n }.ids(total).unwrap();
                    assert_eq!(ids.start, next, "total {total}, {k}/{n}");
                    let len = ids.end - ids.start;
                    // Balanced: every shard has ⌊total/N⌋ or ⌈total/N⌉ rows.
                    assert!(
                        len == total / n || len == total.div_ceil(n),
                        "{total} {k}/{n}"
                    );
                    next = ids.end;
                }
                assert_eq!(next, total);
            }
        }
        let e = Shard { index: 0, count: 7 }.ids(6).unwrap_err();
        assert!(
            e.to_string()
                .contains("N = 7 is more than the scan's 6 samples"),
            "{e}"
        );
        // Huge scans do not overflow.
        let ids = Shard { index: 3, count: 4 }.ids(i64::MAX as u64).unwrap();
        assert_eq!(ids.end, i64::MAX as u64);
    }

    #[test]
    fn part_names_round_trip() {
        let s = Shard {
            index: 12,
            count: 20,
        };
        assert_eq!(part_index(&s.part_name()), Some(12));
        for not in [
            "part-.parquet",
            "part-1a.parquet",
            "part-1.parquet.tmp",
            "part-01.parquet",
            "samples.parquet",
        ] {
            assert_eq!(part_index(not), None, "{not}");
        }
        assert_eq!(padded_part_index("part-01.parquet"), Some(1));
        assert_eq!(padded_part_index("part-00.parquet"), Some(0));
        assert_eq!(padded_part_index("part-1.parquet"), None);
        assert_eq!(padded_part_index("part-0.parquet"), None);
    }
}
