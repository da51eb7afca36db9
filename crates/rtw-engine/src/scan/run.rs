//! Running a scan: samples in parallel, chunk by chunk, into durable parts.
//!
//! The scan's rows `0..N` are cut into chunks of `chunk_size` rows. The
//! workers of a local rayon pool take the samples one at a time in id order
//! (no barrier at a chunk's end), and each chunk, as soon as its rows are in,
//! is collected in `sample_id` order and written, while the workers go on, as
//! one complete, closed Parquet file `DIR/.partial/chunk-NNNNN.parquet`
//! (temporary name, then rename). When all
//! chunks exist they are merged, in order and one batch at a time, into
//! `DIR/samples.parquet` (again through a temporary file), and `.partial` is
//! removed. The merged file has row groups of [`MAX_ROW_GROUP_ROWS`] rows
//! whatever the chunk size, so its footer (held by every writer and reader)
//! stays small and memory stays flat in N: the writer buffers at most one row
//! group.
//!
//! An interrupted run (Ctrl-C sets the `stop` flag; `kill -9` just stops)
//! keeps every finished chunk. `--resume` checks `.partial/manifest.json`
//! against the config, keeps the chunks that are present and valid, and
//! computes the rest; since a row depends only on (seed, sample_id), the
//! result is the same as an uninterrupted run's.
//!
//! A shard (`--shard K/N`, [`Shard`]) is the same scan restricted to the
//! contiguous id range of shard K: its chunks live in `DIR/.partial-K` and
//! its rows end up in `DIR/part-K.parquet`, with the shard and the config
//! hash in the file's metadata, so shards can run at once into one directory
//! and be resumed the same way; `crate::scan::shard::merge_parts` joins them.
//!
//! The simulator is a parameter, so tests can inject a fake one. A sample
//! whose simulation panics becomes a `diverged` row with the panic message in
//! `message`; the scan never aborts for one sample.

use crate::config::ScanConfig;
use crate::files;
use crate::io::metadata::{self, META_CHUNK_WALL_TIME, META_SHARD, META_TOTAL_ROWS};
use crate::io::parquet::{self, MAX_ROW_GROUP_ROWS};
use crate::io::scan_files::concat_scan_files;
use crate::io::scan_rows;
use crate::scan::checkpoint::{
    Checkpoint, Intent, Layout, Resume, check_chunk_size, refuse_other_results, report_unknown,
};
use crate::scan::chunks::{Todo, compute_chunks};
use crate::scan::context::Run;
use crate::scan::lock::Lock;
use crate::scan::one::Simulator;
use crate::scan::partial::remove_partial;
use crate::scan::progress::Progress;
use crate::scan::sample::Sampler;
use crate::scan::shard::Shard;
use crate::scan::workers::{Jobs, worker_pool};
use ::parquet::file::metadata::KeyValue;
use anyhow::Result;
use std::collections::BTreeSet;
use std::num::NonZeroUsize;
use std::path::PathBuf;

/// Rows per chunk unless told otherwise.
pub const DEFAULT_CHUNK_SIZE: usize = 256;

/// How to run a scan (the config says what to run).
#[derive(Clone, Debug)]
pub struct RunSettings {
    /// The scan's directory: `samples.parquet` (or the shard's
    /// `part-K.parquet`) and, while it runs, `.partial/`.
    pub out_dir: PathBuf,
    /// Finish the interrupted run in `out_dir`, keeping its finished chunks.
    pub resume: bool,
    /// Rows per chunk; a resumed run keeps the size it was started with.
    pub chunk_size: NonZeroUsize,
    /// Run only this shard's id range, into `part-K.parquet`.
    pub shard: Option<Shard>,
    /// Write even over another scan's results (or its unfinished run) in
    /// the output directory.
    pub force: bool,
}

/// How a scan ended.
#[derive(Clone, Debug, PartialEq)]
pub enum RunStatus {
    /// `samples` (or the shard's part file) is complete with `rows` rows;
    /// `computed` rows were simulated in this session.
    Complete {
        /// The scan file (or the shard's part file).
        samples: PathBuf,
        /// Its rows.
        rows: u64,
        /// The rows simulated in this session (0: it was already complete).
        computed: u64,
    },
    /// Stopped early; finished chunks are kept in `partial`.
    Interrupted {
        /// The chunks finished and kept.
        chunks_done: u64,
        /// The chunks of the whole run.
        chunks: u64,
        /// The directory that keeps them (`.partial/`).
        partial: PathBuf,
    },
}

/// Runs (or resumes) a scan into `settings.out_dir` on `run.threads`
/// workers: `run.stop` set (by a signal handler, say) ends it after the
/// samples in flight, and `run.progress` watches it.
pub fn run_scan(
    cfg: &ScanConfig,
    settings: &RunSettings,
    sim: Simulator,
    run: &Run,
) -> Result<RunStatus> {
    run_scan_with(cfg, &Sampler::new(cfg), settings, sim, run)
}

/// [`run_scan`] with the rows' parameters from `sampler` (stored points of a
/// refinement round; `cfg` still names the scan, its rows and options).
///
/// The stages: the checks made before any file (shard, threads, chunk
/// size); the output directory claimed (`claim_output`); the resume
/// decision (`Checkpoint::open`); the chunks left computed and written
/// (`write_chunks`); and, once all are there, their merge into the result
/// file (`merge_chunks`).
pub fn run_scan_with(
    cfg: &ScanConfig,
    sampler: &Sampler,
    settings: &RunSettings,
    sim: Simulator,
    run: &Run,
) -> Result<RunStatus> {
    let (stop, progress) = (run.stop, run.progress);
    let total = sampler.total();
    let ids = match settings.shard {
        Some(s) => s.ids(total)?,
        None => 0..total,
    };
    // Started here, before any file is made: the pool refuses a thread
    // count beyond its cap.
    let pool = worker_pool(run.threads)?;
    check_chunk_size(settings.chunk_size.get())?;
    let checkpoint = Checkpoint::new(&settings.out_dir, cfg, ids, settings.shard);
    let rows = checkpoint.rows();
    let _lock = claim_output(&checkpoint.layout, cfg, settings)?;

    let intent = Intent {
        resume: settings.resume,
        force: settings.force,
        chunk_size: settings.chunk_size.get(),
    };
    let (chunk_size, done) = match checkpoint.open(intent, stop, progress)? {
        Resume::Complete => {
            return Ok(RunStatus::Complete {
                samples: checkpoint.layout.samples,
                rows,
                computed: 0,
            });
        }
        Resume::Continue { chunk_size, kept } => (chunk_size, kept),
        Resume::Fresh { chunk_size } => (chunk_size, BTreeSet::new()),
    };

    let metadata = file_metadata(cfg, settings.shard, total);
    let jobs = Jobs {
        sampler,
        options: &cfg.simulation,
        sim,
        stop,
        progress,
    };
    let (written, computed) =
        write_chunks(&pool, &checkpoint, chunk_size, &done, &jobs, &metadata)?;
    let (chunks_done, chunks) = (done.len() as u64 + written, checkpoint.chunks(chunk_size));
    if chunks_done < chunks {
        progress.finish(false);
        return Ok(RunStatus::Interrupted {
            chunks_done,
            chunks,
            partial: checkpoint.layout.partial,
        });
    }
    progress.finish(true);
    merge_chunks(&checkpoint, chunks, metadata, progress)?;
    Ok(RunStatus::Complete {
        samples: checkpoint.layout.samples,
        rows,
        computed,
    })
}

/// Makes the output directory and takes the lock of the result file in
/// `layout`; refuses, unless `force`, a directory that holds another scan's
/// results; and removes the temporary files a killed run, merge or summary
/// of this very result left.
fn claim_output(layout: &Layout, cfg: &ScanConfig, settings: &RunSettings) -> Result<Lock> {
    let out = &settings.out_dir;
    crate::io::destination::output_dir(out, "--out", "a scan's files")?;
    let lock = Lock::acquire(
        &layout.samples,
        &format!("writing {}", layout.samples.display()),
    )?;
    if !settings.force {
        refuse_other_results(out, cfg, settings.shard)?;
    }
    files::remove_stray_temps(&layout.samples)?;
    if settings.shard.is_none() {
        for f in ["summary.json", "summary.md"] {
            files::remove_stray_temps(&out.join(f))?;
        }
    }
    Ok(lock)
}

/// The metadata of the run's chunks and result file: the scan's, and for a
/// shard its `K/N` and the whole scan's rows.
fn file_metadata(cfg: &ScanConfig, shard: Option<Shard>, total: u64) -> Vec<KeyValue> {
    let mut metadata = metadata::scan_metadata(cfg);
    if let Some(s) = shard {
        metadata.push(metadata::kv(META_SHARD, s.to_string()));
        metadata.push(metadata::kv(META_TOTAL_ROWS, total.to_string()));
    }
    metadata
}

/// Computes the chunks of `checkpoint` (of `chunk_size` rows) not in `done`
/// and writes each, as soon as its rows are in, as one closed Parquet file
/// in `.partial` with its wall time: the chunks written and the rows
/// computed.
fn write_chunks(
    pool: &rayon::ThreadPool,
    checkpoint: &Checkpoint<'_>,
    chunk_size: usize,
    done: &BTreeSet<u64>,
    jobs: &Jobs<'_>,
    metadata: &[KeyValue],
) -> Result<(u64, u64)> {
    let range = |c: u64| checkpoint.chunk_ids(chunk_size, c);
    let todo = Todo {
        chunks: checkpoint.chunks(chunk_size),
        range: &range,
        done,
    };
    let (mut written, mut computed) = (0, 0);
    compute_chunks(pool, &todo, jobs, |c, chunk, wall| {
        let mut meta = metadata.to_vec();
        meta.push(metadata::kv(META_CHUNK_WALL_TIME, wall.to_string()));
        let batch = scan_rows::to_batch(&chunk, &jobs.options.robustness);
        parquet::write_file(&checkpoint.layout.chunk(c), &batch, meta)?;
        written += 1;
        computed += chunk.len() as u64;
        Ok(())
    })?;
    Ok((written, computed))
}

/// Joins the `chunks` chunk files, in order, into the result file and
/// removes `.partial` (but what rtw-scan did not make in it).
fn merge_chunks(
    checkpoint: &Checkpoint<'_>,
    chunks: u64,
    metadata: Vec<KeyValue>,
    progress: &dyn Progress,
) -> Result<()> {
    let layout = &checkpoint.layout;
    let chunk_files: Vec<PathBuf> = (0..chunks).map(|c| layout.chunk(c)).collect();
    concat_scan_files(
        &chunk_files,
        checkpoint.ids.clone(),
        &layout.samples,
        MAX_ROW_GROUP_ROWS,
        metadata,
        META_CHUNK_WALL_TIME,
    )?;
    crate::pause_at("merged");
    report_unknown(progress, &layout.partial, &remove_partial(&layout.partial)?);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::parse;
    use crate::io::metadata::VERSION;
    use crate::io::scan_rows::schema;
    use crate::scan::batch::scan_batch;
    use crate::scan::fixtures::{CFG, fake_sim};
    use crate::scan::partial::chunks_on_disk;
    use crate::scan::progress::Silent;
    use arrow_array::{Array, RecordBatch, cast::AsArray};
    use rtw_model::Label;
    use rtw_model::outcome::FailureDetail;
    use rtw_model::{Options, Params};
    use std::path::Path;
    use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

    /// A scan's settings and the threads of the run that takes them.
    struct Case {
        settings: RunSettings,
        threads: Option<NonZeroUsize>,
    }

    impl std::ops::Deref for Case {
        type Target = RunSettings;
        fn deref(&self) -> &RunSettings {
            &self.settings
        }
    }

    impl std::ops::DerefMut for Case {
        fn deref_mut(&mut self) -> &mut RunSettings {
            &mut self.settings
        }
    }

    fn settings(dir: &Path, threads: usize, chunk: usize) -> Case {
        Case {
            settings: RunSettings {
                out_dir: dir.to_path_buf(),
                resume: false,
                chunk_size: NonZeroUsize::new(chunk).unwrap(),
                shard: None,
                force: false,
            },
            threads: NonZeroUsize::new(threads),
        }
    }

    /// [`run_scan`] with the case's threads, stop flag and progress.
    fn scan(
        cfg: &ScanConfig,
        case: &Case,
        sim: Simulator,
        stop: &AtomicBool,
        progress: &dyn Progress,
    ) -> Result<RunStatus> {
        run_scan(
            cfg,
            &case.settings,
            sim,
            &Run::new(progress, stop).on(case.threads),
        )
    }

    /// Every row of a samples file with wall time zeroed.
    fn rows_without_wall_time(path: &Path) -> RecordBatch {
        let input = parquet::open(path, 1 << 20).unwrap();
        let batches: Vec<RecordBatch> = input.reader.map(|b| b.unwrap()).collect();
        let b = arrow_select::concat::concat_batches(&schema(), &batches).unwrap();
        let i = b.schema().index_of("wall_time_s").unwrap();
        let mut cols = b.columns().to_vec();
        cols[i] = std::sync::Arc::new(arrow_array::Float64Array::from(vec![0.0; b.num_rows()]));
        RecordBatch::try_new(schema(), cols).unwrap()
    }

    #[test]
    fn same_rows_for_any_thread_count_and_chunk_size() {
        let cfg = parse(CFG).unwrap();
        let stop = AtomicBool::new(false);
        let a = tempfile::tempdir().unwrap();
        let b = tempfile::tempdir().unwrap();
        scan(&cfg, &settings(a.path(), 1, 5), &fake_sim, &stop, &Silent).unwrap();
        let st = scan(&cfg, &settings(b.path(), 2, 8), &fake_sim, &stop, &Silent).unwrap();
        assert!(
            matches!(
                st,
                RunStatus::Complete {
                    rows: 37,
                    computed: 37,
                    ..
                }
            ),
            "{st:?}"
        );
        let (ra, rb) = (
            rows_without_wall_time(&a.path().join("samples.parquet")),
            rows_without_wall_time(&b.path().join("samples.parquet")),
        );
        assert_eq!(ra.num_rows(), 37);
        assert_eq!(ra, rb);
        assert!(!a.path().join(".partial").exists());
        // The row groups are not the chunks: 37 rows fit in one.
        assert_eq!(row_groups(&a.path().join("samples.parquet")), vec![37]);
        assert_eq!(row_groups(&b.path().join("samples.parquet")), vec![37]);
    }

    /// Rows of each row group of a Parquet file.
    fn row_groups(path: &Path) -> Vec<i64> {
        let f = std::fs::File::open(path).unwrap();
        let meta =
            ::parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder::try_new(f).unwrap();
        meta.metadata()
            .row_groups()
            .iter()
            .map(|g| g.num_rows())
            .collect()
    }

    #[test]
    fn finished_file_has_capped_row_groups_whatever_the_chunks() {
        // Two full row groups and a remainder, from chunks (1000 and 999
        // rows) and shards that do not divide the cap: the row groups are
        // cut at multiples of the cap, not at chunk or part ends, so the
        // footer has ⌈N / cap⌉ entries instead of ⌈N / chunk⌉.
        let n = 2 * MAX_ROW_GROUP_ROWS + 5;
        let cfg = parse(&CFG.replace("samples = 37", &format!("samples = {n}"))).unwrap();
        let stop = AtomicBool::new(false);
        let a = tempfile::tempdir().unwrap();
        let b = tempfile::tempdir().unwrap();
        scan(
            &cfg,
            &settings(a.path(), 2, 1000),
            &fake_sim,
            &stop,
            &Silent,
        )
        .unwrap();
        scan(&cfg, &settings(b.path(), 1, 999), &fake_sim, &stop, &Silent).unwrap();
        // Three shards (parts of 5463 rows, cut into 1000-row chunks), merged.
        let c = tempfile::tempdir().unwrap();
        for index in 0..3 {
            let mut s = settings(c.path(), 2, 1000);
            s.shard = Some(Shard { index, count: 3 });
            scan(&cfg, &s, &fake_sim, &stop, &Silent).unwrap();
        }
        crate::scan::shard::merge_parts(c.path(), false).unwrap();
        let cap = MAX_ROW_GROUP_ROWS as i64;
        for dir in [&a, &b, &c] {
            assert_eq!(
                row_groups(&dir.path().join("samples.parquet")),
                vec![cap, cap, 5]
            );
        }
        let rows = rows_without_wall_time(&a.path().join("samples.parquet"));
        assert_eq!(rows.num_rows(), n);
        for dir in [&b, &c] {
            assert_eq!(
                rows_without_wall_time(&dir.path().join("samples.parquet")),
                rows
            );
        }
    }

    #[test]
    fn panics_become_diverged_rows_with_the_message() {
        let cfg = parse(CFG).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let stop = AtomicBool::new(false);
        scan(
            &cfg,
            &settings(dir.path(), 2, 16),
            &fake_sim,
            &stop,
            &Silent,
        )
        .unwrap();
        let b = rows_without_wall_time(&dir.path().join("samples.parquet"));
        let labels = crate::io::table::label_column(&b).unwrap();
        let rho = crate::io::table::f64_column(&b, "rho").unwrap();
        let msg = b.column_by_name("message").unwrap().as_string::<i32>();
        let failure = b.column_by_name("failure").unwrap().as_string::<i32>();
        let mut panicked = 0;
        for (i, label) in labels.iter().enumerate() {
            if rho.value(i) > 4.75 {
                panicked += 1;
                assert_eq!(*label, Label::Diverged);
                assert!(
                    msg.value(i).contains("fake simulator: rho"),
                    "{}",
                    msg.value(i)
                );
                assert!(msg.value(i).starts_with("panicked at "), "{}", msg.value(i));
            } else if failure.is_null(i) {
                assert!(msg.is_null(i));
            } else {
                // A failure says what it means in words.
                let detail = FailureDetail::ALL
                    .into_iter()
                    .find(|d| d.as_str() == failure.value(i))
                    .unwrap();
                assert_eq!(msg.value(i), detail.describe());
            }
        }
        assert!(panicked > 0, "the seed should draw some rho > 4.75");
    }

    /// A run of `cfg` into `dir` on one thread in chunks of 4 rows, stopped
    /// (as by Ctrl-C) once `n` samples have been taken.
    fn stopped_after(cfg: &ScanConfig, dir: &Path, n: u64) -> RunStatus {
        let stop = AtomicBool::new(false);
        let taken = AtomicU64::new(0);
        let stopping = |p: &Params, o: &Options| {
            if taken.fetch_add(1, Ordering::SeqCst) >= n {
                stop.store(true, Ordering::SeqCst);
            }
            fake_sim(p, o)
        };
        scan(cfg, &settings(dir, 1, 4), &stopping, &stop, &Silent).unwrap()
    }

    #[test]
    fn interrupted_run_resumes_to_the_same_rows() {
        let cfg = parse(CFG).unwrap();
        let full = tempfile::tempdir().unwrap();
        let part = tempfile::tempdir().unwrap();
        let never = AtomicBool::new(false);
        scan(
            &cfg,
            &settings(full.path(), 2, 4),
            &fake_sim,
            &never,
            &Silent,
        )
        .unwrap();

        // Stop after 7 samples: the chunk in progress is dropped.
        let st = stopped_after(&cfg, part.path(), 6);
        let RunStatus::Interrupted {
            chunks_done,
            chunks,
            ..
        } = st
        else {
            panic!("{st:?}")
        };
        assert_eq!((chunks_done, chunks), (1, 10));
        assert!(!part.path().join("samples.parquet").exists());

        // Without --resume the unfinished run is not silently dropped.
        let e = scan(
            &cfg,
            &settings(part.path(), 1, 4),
            &fake_sim,
            &never,
            &Silent,
        )
        .unwrap_err();
        assert!(e.to_string().contains("--resume"), "{e}");
        // A different config cannot resume it.
        let other = parse(&CFG.replace("seed = 11", "seed = 12")).unwrap();
        let mut s = settings(part.path(), 2, 4);
        s.resume = true;
        let e = scan(&other, &s, &fake_sim, &never, &Silent).unwrap_err();
        assert!(e.to_string().contains("different config"), "{e}");
        // A stray temporary file and a corrupt chunk are cleaned up.
        std::fs::write(
            part.path().join(".partial/.chunk-00003.parquet.x.tmp"),
            b"junk",
        )
        .unwrap();
        std::fs::write(part.path().join(".partial/chunk-00002.parquet"), b"junk").unwrap();
        let st = scan(&cfg, &s, &fake_sim, &never, &Silent).unwrap();
        assert!(
            matches!(st, RunStatus::Complete { computed: 33, .. }),
            "{st:?}"
        );
        assert_eq!(
            rows_without_wall_time(&full.path().join("samples.parquet")),
            rows_without_wall_time(&part.path().join("samples.parquet"))
        );
        // Resuming a finished run does nothing.
        let st = scan(&cfg, &s, &fake_sim, &never, &Silent).unwrap();
        assert!(
            matches!(st, RunStatus::Complete { computed: 0, .. }),
            "{st:?}"
        );
    }

    #[test]
    fn open_says_what_it_found_fresh_continue_or_complete() {
        let cfg = parse(CFG).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let never = AtomicBool::new(false);
        let checkpoint = Checkpoint::new(dir.path(), &cfg, 0..37, None);
        let intent = |resume, chunk_size| Intent {
            resume,
            force: false,
            chunk_size,
        };
        // An empty directory: a new run in the asked chunk size, its
        // manifest written.
        let found = checkpoint.open(intent(true, 8), &never, &Silent).unwrap();
        assert_eq!(found, Resume::Fresh { chunk_size: 8 });
        assert!(checkpoint.layout.manifest().is_file());
        std::fs::remove_dir_all(&checkpoint.layout.partial).unwrap();

        // A run stopped with chunks of 4 rows: continued in its own chunk
        // size, whatever is asked, keeping exactly the chunks on disk.
        stopped_after(&cfg, dir.path(), 10);
        let on_disk: BTreeSet<u64> = chunks_on_disk(&checkpoint.layout.partial)
            .unwrap()
            .into_iter()
            .collect();
        assert!(on_disk.len() >= 2, "{on_disk:?}");
        let found = checkpoint.open(intent(true, 8), &never, &Silent).unwrap();
        assert_eq!(
            found,
            Resume::Continue {
                chunk_size: 4,
                kept: on_disk
            }
        );

        // Finished, then resumed again: complete, nothing to compute.
        let mut s = settings(dir.path(), 1, 4);
        s.resume = true;
        scan(&cfg, &s, &fake_sim, &never, &Silent).unwrap();
        let found = checkpoint.open(intent(true, 8), &never, &Silent).unwrap();
        assert_eq!(found, Resume::Complete);
        // Without --resume too, since this version made it: nothing to
        // compute (the same command run twice); with --force, computed anew.
        let found = checkpoint.open(intent(false, 8), &never, &Silent).unwrap();
        assert_eq!(found, Resume::Complete);
        let forced = Intent {
            force: true,
            ..intent(false, 8)
        };
        let found = checkpoint.open(forced, &never, &Silent).unwrap();
        assert_eq!(found, Resume::Fresh { chunk_size: 8 });
    }

    #[test]
    fn a_finished_scan_of_another_version_run_again_is_computed_anew() {
        // Its rows may differ from this build's: a run without --resume
        // replaces them with this version's, as before.
        let cfg = parse(CFG).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let never = AtomicBool::new(false);
        scan(
            &cfg,
            &settings(dir.path(), 1, 8),
            &fake_sim,
            &never,
            &Silent,
        )
        .unwrap();
        let samples = dir.path().join("samples.parquet");
        let input = parquet::open(&samples, 64).unwrap();
        let meta = input
            .metadata
            .iter()
            .map(|(k, v)| {
                let v = if k == metadata::META_VERSION {
                    "0.0.9"
                } else {
                    v
                };
                metadata::kv(k, v.to_string())
            })
            .collect();
        let batches: Vec<RecordBatch> = input.reader.map(|b| b.unwrap()).collect();
        assert_eq!(batches.len(), 1);
        parquet::write_file(&samples, &batches[0], meta).unwrap();
        let st = scan(
            &cfg,
            &settings(dir.path(), 1, 8),
            &fake_sim,
            &never,
            &Silent,
        )
        .unwrap();
        assert!(
            matches!(st, RunStatus::Complete { computed: 37, .. }),
            "{st:?}"
        );
        let file = parquet::open(&samples, 1).unwrap();
        assert_eq!(file.metadata[metadata::META_VERSION], VERSION);
    }

    #[test]
    fn a_chunk_of_another_rtw_scan_version_is_computed_again() {
        // A chunk that says another version (copied in, or kept under a lost
        // manifest) is not mixed into this version's file.
        let cfg = parse(CFG).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let never = AtomicBool::new(false);
        stopped_after(&cfg, dir.path(), 10);
        let chunk = dir.path().join(".partial/chunk-00000.parquet");
        let input = parquet::open(&chunk, 64).unwrap();
        let meta = input
            .metadata
            .iter()
            .filter(|(k, _)| k.as_str() != metadata::META_CONTENT_HASH)
            .map(|(k, v)| {
                let v = if k == metadata::META_VERSION {
                    "0.0.9"
                } else {
                    v
                };
                metadata::kv(k, v.to_string())
            })
            .collect();
        let batches: Vec<RecordBatch> = input.reader.map(|b| b.unwrap()).collect();
        parquet::write_file(&chunk, &batches[0], meta).unwrap();
        let kept = chunks_on_disk(&dir.path().join(".partial")).unwrap().len() as u64;
        assert!(kept >= 2, "{kept} chunks");
        let mut s = settings(dir.path(), 2, 4);
        s.resume = true;
        let st = scan(&cfg, &s, &fake_sim, &never, &Silent).unwrap();
        // Chunk 0's 4 rows are computed again with the others not kept.
        let computed = 37 - 4 * (kept - 1);
        assert!(
            matches!(st, RunStatus::Complete { computed: c, .. } if c == computed),
            "{st:?}, expected {computed} computed"
        );
        let file = parquet::open(&dir.path().join("samples.parquet"), 1).unwrap();
        assert_eq!(file.metadata[metadata::META_VERSION], VERSION);
    }

    #[test]
    fn scan_batch_holds_the_rows_of_run_scan() {
        // The real simulator, a few short runs: the in-memory scan (Python's
        // `rtw.scan`) and the file are the same rows but the wall time.
        let cfg = parse(&CFG.replace("samples = 37", "samples = 5")).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let never = AtomicBool::new(false);
        let sim: Simulator = &rtw_model::simulate;
        scan(&cfg, &settings(dir.path(), 2, 2), sim, &never, &Silent).unwrap();
        let done = AtomicU64::new(0);
        let b = scan_batch(&cfg, NonZeroUsize::new(2), &never, &done)
            .unwrap()
            .unwrap();
        assert_eq!(done.load(Ordering::SeqCst), 5);
        let meta = b.schema().metadata().clone();
        assert_eq!(meta["rtw.config"], cfg.to_toml());
        assert_eq!(meta["rtw.config_hash"], cfg.hash());
        assert!(meta["rtw.wall_time_s"].parse::<f64>().unwrap() > 0.0);
        let i = b.schema().index_of("wall_time_s").unwrap();
        let mut cols = b.columns().to_vec();
        cols[i] = std::sync::Arc::new(arrow_array::Float64Array::from(vec![0.0; b.num_rows()]));
        let b = RecordBatch::try_new(schema(), cols).unwrap();
        assert_eq!(
            b,
            rows_without_wall_time(&dir.path().join("samples.parquet"))
        );
        // Stopped before it starts: no rows, no error.
        let stopped = AtomicBool::new(true);
        assert!(scan_batch(&cfg, None, &stopped, &done).unwrap().is_none());
    }
}
