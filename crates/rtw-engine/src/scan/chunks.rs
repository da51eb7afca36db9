//! The chunk scheduler of a run: the workers take the samples one at a time
//! in id order, and each chunk is handed over whole, in id order, as soon as
//! its last row is in (see [`compute_chunks`]).

use crate::io::scan_rows::Row;
use crate::scan::workers::Jobs;
use anyhow::Result;
use std::collections::{BTreeMap, BTreeSet};
use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, mpsc};
use std::time::Instant;

/// The chunks a run still has to compute: those of `0..chunks` not in
/// `done`, chunk `c` holding the sample ids `range(c)`.
pub(crate) struct Todo<'a> {
    pub(crate) chunks: u64,
    pub(crate) range: &'a (dyn Fn(u64) -> Range<u64> + Sync),
    pub(crate) done: &'a BTreeSet<u64>,
}

impl Todo<'_> {
    /// The first sample to do from chunk `c` on: its chunk and id (the chunk
    /// is `chunks` when none is left).
    fn first_from(&self, mut c: u64) -> (u64, u64) {
        while c < self.chunks && self.done.contains(&c) {
            c += 1;
        }
        let id = if c < self.chunks {
            (self.range)(c).start
        } else {
            0
        };
        (c, id)
    }
}

/// A chunk in progress: its rows so far, by position, and how many are in.
struct OpenChunk {
    rows: Vec<Option<Row>>,
    filled: usize,
}

/// Computes the rows of the chunks of `todo` on `pool`, and hands each
/// chunk, in id order, to `finished` on this thread as soon as its last row
/// is in: `finished(c, rows, wall)`, `wall` the time since the previous
/// chunk was handed over (or the start), so that the chunks' times add up to
/// the run's.
///
/// The workers take the samples one at a time in id order, so none waits at
/// a chunk's end for the others (a barrier per chunk cost 2.6 % of the paper
/// scan on 2 threads), the chunks finish about in order, and this thread
/// writes a finished chunk while the workers go on. Nothing is built per
/// chunk or per sample ahead of time (a scan may have 10¹² samples). Once
/// `jobs.stop` is set, the samples in flight stop at their runs' next step
/// and are dropped with the chunks they belong to; the chunks finished
/// before are still handed over: at most the chunks in progress are lost. An error from `finished` stops the workers the same
/// way and is returned.
pub(crate) fn compute_chunks(
    pool: &rayon::ThreadPool,
    todo: &Todo<'_>,
    jobs: &Jobs<'_>,
    mut finished: impl FnMut(u64, Vec<Row>, f64) -> Result<()>,
) -> Result<()> {
    // The next sample to hand out: its chunk and id.
    let cursor = Mutex::new(todo.first_from(0));
    let take = || {
        let mut cur = cursor.lock().unwrap_or_else(|e| e.into_inner());
        let (c, id) = *cur;
        if c >= todo.chunks {
            return None;
        }
        *cur = if id + 1 < (todo.range)(c).end {
            (c, id + 1)
        } else {
            todo.first_from(c + 1)
        };
        Some((c, id))
    };
    let halt = AtomicBool::new(false);
    let stopped = || jobs.stop.load(Ordering::SeqCst) || halt.load(Ordering::SeqCst);
    // The chunks in progress. The worker that puts a chunk's last row in
    // sends the chunk, so this thread wakes once per chunk, not per row.
    let open: Mutex<BTreeMap<u64, OpenChunk>> = Mutex::new(BTreeMap::new());
    let put = |c: u64, row: Row| -> Option<Vec<Row>> {
        let ids = (todo.range)(c);
        let mut open = open.lock().unwrap_or_else(|e| e.into_inner());
        // Grown as the rows come (they come about in order), never
        // allocated for the whole chunk ahead of them.
        let chunk = open.entry(c).or_insert_with(|| OpenChunk {
            rows: Vec::new(),
            filled: 0,
        });
        let at = (row.sample_id - ids.start) as usize;
        if chunk.rows.len() <= at {
            chunk.rows.resize_with(at + 1, || None);
        }
        chunk.rows[at] = Some(row);
        chunk.filled += 1;
        if (chunk.filled as u64) < ids.end - ids.start {
            return None;
        }
        let chunk = open.remove(&c).expect("the chunk just filled");
        Some(chunk.rows.into_iter().flatten().collect())
    };
    let (tx, rx) = mpsc::channel::<(u64, Vec<Row>)>();
    let mut outcome = Ok(());
    pool.in_place_scope(|scope| {
        for _ in 0..pool.current_num_threads() {
            let tx = tx.clone();
            let (take, put, stopped) = (&take, &put, &stopped);
            scope.spawn(move |_| {
                while !stopped() {
                    let Some((c, id)) = take() else { break };
                    let Some(row) = jobs.row(id) else { break };
                    if let Some(rows) = put(c, row)
                        && tx.send((c, rows)).is_err()
                    {
                        break;
                    }
                }
            });
        }
        drop(tx);
        let mut since = Instant::now();
        for (c, rows) in rx {
            if outcome.is_err() {
                continue;
            }
            let wall = since.elapsed().as_secs_f64();
            since = Instant::now();
            if let Err(e) = finished(c, rows, wall) {
                halt.store(true, Ordering::SeqCst);
                outcome = Err(e);
            }
        }
    });
    outcome
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::parse;
    use crate::scan::fixtures::{CFG, fake_sim};
    use crate::scan::one::Simulator;
    use crate::scan::progress::Silent;
    use crate::scan::sample::Sampler;
    use crate::scan::workers::worker_pool;
    use anyhow::bail;
    use rtw_model::{Options, Params};
    use std::num::NonZeroUsize;
    use std::sync::atomic::AtomicU64;
    use std::time::Duration;

    /// The scan's chunks of 4 rows of CFG's 37 samples, every one to do, on
    /// 2 workers, with `sim`; `finished` as [`compute_chunks`]'.
    fn chunks_of_cfg(
        sim: Simulator,
        finished: impl FnMut(u64, Vec<Row>, f64) -> Result<()>,
    ) -> Result<()> {
        let cfg = parse(CFG).unwrap();
        let pool = worker_pool(NonZeroUsize::new(2)).unwrap();
        let stop = AtomicBool::new(false);
        let sampler = Sampler::new(&cfg);
        let jobs = Jobs {
            sampler: &sampler,
            options: &cfg.simulation,
            sim,
            stop: &stop,
            progress: &Silent,
        };
        let range = |c: u64| c * 4..((c + 1) * 4).min(37);
        let done = BTreeSet::new();
        let todo = Todo {
            chunks: 10,
            range: &range,
            done: &done,
        };
        compute_chunks(&pool, &todo, &jobs, finished)
    }

    #[test]
    fn a_slow_sample_does_not_hold_back_the_chunks_after_it() {
        // The first sample taken (chunk 0's) takes 400 ms, the others next
        // to nothing: the other worker finishes the other nine chunks
        // meanwhile, each handed over whole and in id order. With a barrier
        // at each chunk's end, chunk 0 would come first.
        let calls = AtomicU64::new(0);
        let sim = |p: &Params, o: &Options| {
            if calls.fetch_add(1, Ordering::SeqCst) == 0 {
                std::thread::sleep(Duration::from_millis(400));
            }
            fake_sim(p, o)
        };
        let mut order = Vec::new();
        chunks_of_cfg(&sim, |c, rows, wall| {
            let ids: Vec<u64> = rows.iter().map(|r| r.sample_id).collect();
            assert_eq!(ids, (c * 4..((c + 1) * 4).min(37)).collect::<Vec<_>>());
            assert!(wall >= 0.0);
            order.push(c);
            Ok(())
        })
        .unwrap();
        assert_eq!(order.len(), 10, "{order:?}");
        assert_eq!(order.last(), Some(&0), "{order:?}");
        assert_eq!(calls.load(Ordering::SeqCst), 37);
    }

    #[test]
    fn a_chunk_that_cannot_be_written_stops_the_workers() {
        // Writing chunk 2 fails: the error comes back, and the workers stop
        // after the rows in flight instead of computing the rest (20 ms a
        // sample: the 25 samples after chunk 2 would take 250 ms on 2
        // workers, room for a slow machine to hand the error over late).
        let calls = AtomicU64::new(0);
        let sim = |p: &Params, o: &Options| {
            calls.fetch_add(1, Ordering::SeqCst);
            std::thread::sleep(Duration::from_millis(20));
            fake_sim(p, o)
        };
        let e = chunks_of_cfg(&sim, |c, _, _| {
            if c == 2 {
                bail!("disk full (test)")
            }
            Ok(())
        })
        .unwrap_err();
        assert!(e.to_string().contains("disk full (test)"), "{e}");
        let n = calls.load(Ordering::SeqCst);
        assert!((12..=30).contains(&n), "{n} samples computed");
    }
}
